"""Every relative link of README.md and docs/**/*.md names a file that exists, and every #anchor a heading of its
page (scripts/check_doc_links.py): moving a section between pages cannot leave a link behind."""
import os
import shutil
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(REPO, 'scripts', 'check_doc_links.py')


def check(repo):
    return subprocess.run([sys.executable, SCRIPT, '--repo', repo], capture_output=True, text=True)


def test_every_link_of_the_docs_resolves():
    r = check(REPO)
    assert r.returncode == 0, r.stderr


def test_a_missing_page_or_heading_is_reported(tmp_path):
    shutil.copy(os.path.join(REPO, 'README.md'), tmp_path / 'README.md')
    shutil.copytree(os.path.join(REPO, 'docs'), tmp_path / 'docs')
    (tmp_path / 'docs' / 'broken.md').write_text('[a](gone.md), [b](physics.md#no-such-heading), `[c](code.md)`\n')
    r = check(str(tmp_path))
    assert r.returncode == 1, r.stderr
    assert 'docs/broken.md:1: gone.md: no such file' in r.stderr, r.stderr
    assert 'no heading makes the anchor #no-such-heading' in r.stderr, r.stderr
    assert 'code.md' not in r.stderr, r.stderr
