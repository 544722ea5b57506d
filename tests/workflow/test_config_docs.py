"""config/README.md is generated from config/schema.yaml, and every key there is described."""

from pathlib import Path

from chainchaos.workflow import config_docs

ROOT = Path(__file__).resolve().parents[2]


def test_every_config_key_has_a_description():
    assert config_docs.undescribed(config_docs.config_schema()) == []


def test_committed_config_readme_is_the_generated_one():
    committed = (ROOT / config_docs.README).read_text()
    assert committed == config_docs.render(), "config/README.md is stale: run python -m chainchaos.workflow.config_docs"


def test_readme_lists_every_key_with_its_type_and_default():
    schema = config_docs.config_schema(own_models=False)
    text = config_docs.render(schema)
    for key in config_docs.keys(schema):
        assert f"| `{key.path}` |" in text, key.path
    assert "| `figures.dpi` | integer (>= 50, <= 1200) |" in text
    assert "| `ensemble.convention` | string: `potential`, `period_averaged` | `potential` |" in text
    # a key shared through a YAML anchor points to where it is described first
    assert "| `scenes.<scene name>.dt` | number (> 0) |  | as `simulation.dt`:" in text


def test_an_undescribed_key_is_named():
    schema = {"type": "object", "properties": {"a": {"type": "object", "description": "block",
                                                     "properties": {"b": {"type": "integer"}}}}}
    assert config_docs.undescribed(schema) == ["a.b"]
