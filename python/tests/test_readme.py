"""The README's Python and C# examples are the files CI runs, verbatim."""
from conftest import SOURCE


def test_readme_quotes_the_examples_ci_runs():
    readme = (SOURCE / "README.md").read_text()
    for path in ("python/examples/readme_example.py", "bindings/csharp/ReadmeExample.cs"):
        code = (SOURCE / path).read_text()
        assert code in readme, f"README.md no longer quotes {path} verbatim"
