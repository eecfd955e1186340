"""The README and docs/ as a newcomer reads them: every generated table equal to what
bench/docs_tables.py writes from docs/data (so neither stale nor edited by hand), every relative
link and anchor resolving, the pages' sizes, and every `sh` block run as written from a folder
outside the checkout.

    python3 -m pytest -q tests/test_docs_pages.py    # SSGI_BUILD_DIR: the build (default build/)

A block runs with the convention the README states: the programs called by name, the shipped
scenes by theirs, from any folder; here an empty temporary folder, with the build's programs
first on PATH and nothing of the checkout beside it. A block preceded by the line
`<!-- docs-test: skip: REASON -->` is not run (it installs, builds, or takes over a minute)."""
import os
import pathlib
import re
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
import docs_tables  # noqa: E402

BUILD = pathlib.Path(os.environ.get("SSGI_BUILD_DIR", ROOT / "build"))
PAGES = [ROOT / "README.md", ROOT / "CHANGELOG.md"] + sorted((ROOT / "docs").glob("*.md"))
HASH = re.compile(r"\b[0-9a-f]{7,40}\b")
SKIP = re.compile(r"<!-- docs-test: skip: (.+?) -->")
LINK = re.compile(r"\]\(([^)\s]+)\)")


def rel(path):
    return str(path.relative_to(ROOT))


def test_generated_tables_equal_their_data():
    stale = docs_tables.run(check=True)
    assert not stale, ("these tables differ from docs/data (run python3 bench/docs_tables.py; "
                       "edit the data, not the tables): %s" % ", ".join(stale))


def test_every_generated_table_is_marked_once():
    for page, name, _ in docs_tables.TABLES:
        text = (ROOT / page).read_text()
        assert text.count(docs_tables.BEGIN % name) == 1, (page, name)
        assert text.count(docs_tables.END % name) == 1, (page, name)


def slug(heading):
    """GitHub's anchor for a heading."""
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(path):
    text = path.read_text()
    found = {slug(m.group(1)) for m in re.finditer(r"(?m)^#+ (.+)$", strip_code(text))}
    found |= set(re.findall(r'<a id="([^"]+)"', text))
    return found


def strip_code(text):
    return re.sub(r"(?ms)^```.*?^```", "", text)


@pytest.mark.parametrize("page", PAGES, ids=rel)
def test_links_resolve(page):
    bad = []
    for target in LINK.findall(strip_code(page.read_text())):
        if re.match(r"[a-z]+:", target):
            continue
        path, _, anchor = target.partition("#")
        dest = (page.parent / path).resolve() if path else page
        if not dest.exists():
            bad.append(target)
        elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            bad.append(target + " (no such heading)")
    assert not bad, "%s: broken links: %s" % (rel(page), ", ".join(bad))


def test_sizes_and_hashes():
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= 150, "README.md over 150 lines"
    assert not HASH.findall(readme), "README.md names commits: %s" % HASH.findall(readme)
    for page in sorted((ROOT / "docs").glob("*.md")):
        assert len(page.read_text().splitlines()) <= 450, "%s over 450 lines" % rel(page)


def test_docs_name_at_most_60_commits():
    """docs/ names a commit only where a table says what measured it: 60 at most in all
    (strings that look like hashes but name no commit of this repository do not count)."""
    found = [h for page in sorted((ROOT / "docs").glob("*.md"))
             for h in HASH.findall(page.read_text())]
    check = subprocess.run(["git", "-C", str(ROOT), "cat-file", "--batch-check"],
                           input="".join(h + "^{commit}\n" for h in found),
                           capture_output=True, text=True)
    if check.returncode != 0:
        pytest.skip("no git repository to tell commits from other hex strings")
    commits = [line for line in check.stdout.splitlines() if line.endswith(" commit") or
               " commit " in line]
    assert len(commits) <= 60, "docs/ names %d commits (at most 60)" % len(commits)


def blocks():
    """(page, line, text, skip reason or None) of every sh block of README.md and docs/."""
    out = []
    for page in [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md")):
        lines = page.read_text().splitlines()
        i = 0
        while i < len(lines):
            if lines[i].strip() in ("```sh", "```bash"):
                start = i
                i += 1
                body = []
                while not lines[i].startswith("```"):
                    body.append(lines[i])
                    i += 1
                skip = SKIP.search(lines[start - 1]) if start > 0 else None
                out.append((rel(page), start + 1, "\n".join(body),
                            skip.group(1) if skip else None))
            i += 1
    return out


@pytest.mark.parametrize("page,line,text,skip",
                         [pytest.param(*b, id="%s:%d" % b[:2]) for b in blocks()])
def test_shell_block_runs(page, line, text, skip, tmp_path):
    if skip:
        pytest.skip(skip)
    if not (BUILD / "render").exists():
        pytest.skip("no build in %s (set SSGI_BUILD_DIR)" % BUILD)
    folder = tmp_path / "anywhere"
    folder.mkdir()
    env = dict(os.environ, PATH=str(BUILD.resolve()) + os.pathsep + os.environ.get("PATH", ""))
    run = subprocess.run(["bash", "-euo", "pipefail", "-c", text], cwd=folder, env=env,
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, "%s:%d: exit %d\n%s\n%s" % (page, line, run.returncode,
                                                           run.stdout[-2000:], run.stderr[-2000:])
