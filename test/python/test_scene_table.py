"""docs/scenes.md's table of the shipped scenes is generated (scripts/scene_table.py) from each scene's description:
the repository's table is up to date, and the check fails when a scene is added or its description changes
without regenerating, or when a scene has no one-line description."""
import os
import shutil
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(REPO, 'scripts', 'scene_table.py')


def check(repo):
    return subprocess.run([sys.executable, SCRIPT, '--check', '--repo', repo], capture_output=True, text=True)


def copy_of_repo(tmp_path):
    """docs/scenes.md and config/scenes/ of the repository in tmp_path (what the script reads)."""
    (tmp_path / 'docs').mkdir()
    shutil.copy(os.path.join(REPO, 'docs', 'scenes.md'), tmp_path / 'docs' / 'scenes.md')
    shutil.copytree(os.path.join(REPO, 'config', 'scenes'), tmp_path / 'config' / 'scenes')
    return tmp_path


def test_scenes_table_is_up_to_date():
    r = check(REPO)
    assert r.returncode == 0, r.stderr
    with open(os.path.join(REPO, 'docs', 'scenes.md')) as f:
        page = f.read()
    for name in os.listdir(os.path.join(REPO, 'config', 'scenes')):
        assert '| `%s` |' % name[:-len('.yaml')] in page, name


def test_check_fails_when_a_scene_is_added_or_its_description_changes(tmp_path):
    repo = copy_of_repo(tmp_path)
    scenes = repo / 'config' / 'scenes'
    (scenes / 'new_one.yaml').write_text('description: a new scene\ntop: aluminium\nfriction: pmma\n')
    r = check(str(repo))
    assert r.returncode == 1 and 'new_one' in r.stderr and 'out of date' in r.stderr, r.stderr
    subprocess.run([sys.executable, SCRIPT, '--repo', str(repo)], check=True, capture_output=True)
    assert check(str(repo)).returncode == 0
    default = scenes / 'default.yaml'
    default.write_text(default.read_text().replace('description: ', 'description: changed, '))
    r = check(str(repo))
    assert r.returncode == 1 and 'changed, ' in r.stderr, r.stderr


def test_a_scene_without_a_description_is_an_error(tmp_path):
    repo = copy_of_repo(tmp_path)
    (repo / 'config' / 'scenes' / 'bare.yaml').write_text('top: aluminium\nfriction: pmma\n')
    r = check(str(repo))
    assert r.returncode == 1 and 'bare.yaml: description: must be one line' in r.stderr, r.stderr
