"""`launchkit build --symlink-install`: Python code, data files and interface files are links
to the source, so an edit shows without building again; pip's RECORD never lists a source file
(a `pip uninstall` could otherwise delete the user's code through the link)."""

from __future__ import annotations

from pathlib import Path

from workspaces import (
    environment,
    in_sourced_shell,
    interface_package,
    launchkit_build,
    python_package,
    write_package,
)

SAY = 'def main():\n    print("version one")\n'


def test_an_edit_to_the_source_shows_without_building_again(tmp_path: Path) -> None:
    root = tmp_path / "ws"
    files = python_package("edit_py", {"say": SAY})
    files["launch/say.launch.xml"] = '<launch>\n  <node pkg="edit_py" exec="say"/>\n</launch>\n'
    source = write_package(root / "src", "edit_py", files)
    msgs = write_package(
        root / "src", "edit_msgs", interface_package("edit_msgs", {"msg/A.msg": "int8 a\n"})
    )
    env = environment(tmp_path)
    built = launchkit_build(root, "--symlink-install", env=env)
    assert built.returncode == 0, built.stdout + built.stderr

    before = in_sourced_shell(root, "launchkit exec edit_py say", env, tmp_path)
    assert before.stdout == "version one\n", before.stderr
    (source / "edit_py" / "say.py").write_text(SAY.replace("one", "two"))
    (source / "edit_py" / "extra.py").write_text("WORD = 'new module'\n")
    (source / "launch" / "say.launch.xml").write_text("<launch/>\n")
    (msgs / "msg" / "A.msg").write_text("int16 a\n")
    after = in_sourced_shell(
        root,
        "launchkit exec edit_py say && python -c 'import edit_py.extra as e; print(e.WORD)'"
        ' && cat "$(launchkit pkg share edit_py)/launch/say.launch.xml"'
        ' "$(launchkit pkg share edit_msgs)/msg/A.msg"',
        env,
        tmp_path,
    )
    assert after.stdout == "version two\nnew module\n<launch/>\nint16 a\n", after.stderr

    prefix = root / "install" / "edit_py"
    (site,) = prefix.glob("lib/python3.*/site-packages")
    assert (site / "edit_py").resolve() == (source / "edit_py").resolve()
    (record,) = site.glob("edit_py-*.dist-info/RECORD")
    listed = [line.split(",")[0] for line in record.read_text().splitlines()]
    assert "edit_py" in listed and not [p for p in listed if p.startswith("edit_py/")]
    assert "../../edit_py/say" in listed  # the script, where it was moved


def test_building_again_without_symlinks_copies(tmp_path: Path) -> None:
    root = tmp_path / "ws"
    source = write_package(root / "src", "copy_py", python_package("copy_py", {"say": SAY}))
    env = environment(tmp_path)
    assert launchkit_build(root, "--symlink-install", env=env).returncode == 0
    rebuilt = launchkit_build(root, env=env)
    assert rebuilt.returncode == 0, rebuilt.stdout
    (site,) = (root / "install" / "copy_py").glob("lib/python3.*/site-packages")
    assert not (site / "copy_py").is_symlink()
    assert (source / "copy_py" / "say.py").is_file()  # the old link's target is untouched
    (source / "copy_py" / "say.py").write_text(SAY.replace("one", "two"))
    ran = in_sourced_shell(root, "launchkit exec copy_py say", env, tmp_path)
    assert ran.stdout == "version one\n"
