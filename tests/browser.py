"""Pages opened in a real browser: Debian's Chromium (installed by workflow/setup.sh as root),
driven by Playwright (the test extra; its own browsers are not downloaded, the system's is used).

``console_errors(paths, root)`` loads each local HTML file and returns, per file, the console
messages of level error and the uncaught exceptions it raised; an empty list is a page that loads
cleanly. With ``root`` the pages are served over HTTP from that folder on the loopback address, as
a site is read (a site's search index, for one, is not loaded from file:// URLs)."""

import contextlib
import functools
import shutil
import threading
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

import pytest

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
#: As the machine's own check starts it: headless, no sandbox (root), and no background traffic,
#: which this machine's closed network would refuse.
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
        "--disable-component-update", "--disable-sync"]


def browser_or_skip():
    """Playwright's sync API, or a skip naming what is missing."""
    sync = pytest.importorskip("playwright.sync_api", reason="playwright is not installed: pip install -e '.[test]'")
    if not Path(CHROMIUM).exists():
        pytest.skip("Chromium is not installed: apt-get install chromium (workflow/setup.sh does, as root)")
    return sync.sync_playwright


@contextlib.contextmanager
def served(root):
    """An HTTP server of the folder ``root`` on 127.0.0.1 (a free port), for the duration: its URL."""

    class Quiet(SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    server = ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(root)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


def console_errors(paths, root=None, settle_ms: int = 500) -> dict[str, list[str]]:
    """Per page (a local file; under ``root`` served over HTTP), its console errors and uncaught
    exceptions after it loaded."""
    sync_playwright = browser_or_skip()
    found = {}
    with sync_playwright() as p, (served(root) if root else contextlib.nullcontext()) as base:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        try:
            for path in paths:
                page = browser.new_page()
                errors = []
                page.on("console", lambda m, errors=errors: errors.append(f"console: {m.text}") if m.type == "error" else None)
                page.on("pageerror", lambda e, errors=errors: errors.append(f"uncaught: {e}"))
                url = f"{base}/{Path(path).relative_to(root).as_posix()}" if root else Path(path).resolve().as_uri()
                page.goto(url, wait_until="load")
                page.wait_for_timeout(settle_ms)
                found[str(path)] = errors
                page.close()
        finally:
            browser.close()
    return found
