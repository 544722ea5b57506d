#!/usr/bin/env bash
# Set up a fresh machine from the project's own files: the Python package with the workflow, test and
# docs extras at the locked versions, and (as root, from Debian's packages) the TeX system that
# builds the manuscript and the Chromium that the browser tests drive.
set -euo pipefail
cd "$(dirname "$0")/.."
# The exact versions of requirements/lock.txt, each wheel checked against its hash, so that every
# machine runs the same libraries (requirements/README.md: how the lock is made and updated).
python -m pip install --quiet --disable-pip-version-check --require-hashes -r requirements/lock.txt
# The package itself: its dependencies are the locked ones above, so pip must not resolve them again.
python -m pip install --quiet --disable-pip-version-check --no-deps -e .
# TeX for the manuscript; Chromium for the tests that open the report and the docs in a browser.
debian_packages="texlive-latex-base texlive-latex-recommended texlive-publishers latexmk poppler-utils chromium"
if ! command -v latexmk >/dev/null || ! command -v pdftotext >/dev/null || ! kpsewhich revtex4-2.cls >/dev/null 2>&1 \
    || ! command -v chromium >/dev/null; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $debian_packages >/dev/null
  else
    echo "setup: the manuscript needs TeX and the browser tests Chromium; install the Debian packages: $debian_packages" >&2
  fi
fi
