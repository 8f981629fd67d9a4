"""`blender -b -P headless.py -- run` from the checkout (bind-mounted at /fibrilfit): the
package loads from its own folder, no installed extension needed, and gives the bpy module's
verdict."""
from realblender.helpers import OUT, chroot, inside, module, own_lines, read_json


def test_headless_script_runs_on_the_real_blender():
    real, ref = OUT / "headless-blender.json", OUT / "headless-module.json"
    OUT.mkdir(parents=True, exist_ok=True)
    args = "--layers 10 --linker 5 --seed 4"
    cp = chroot(f"blender -b --factory-startup -P headless.py -- run {args} --json {inside(real)}")
    assert cp.returncode == 0, cp.stdout[-2000:] + cp.stderr[-2000:]
    assert "FibrilFit 0.1.0 on Blender 4.3.2" in cp.stdout
    assert module(["run", *args.split(), "--json", str(ref)]).returncode == 0
    a, b = read_json(real), read_json(ref)
    assert a["blender_version"] == "4.3.2"
    assert (a["verdict"], a["accommodated"], a["params"]) == (b["verdict"], b["accommodated"],
                                                              b["params"])


def test_headless_script_refuses_a_bad_option_with_one_line():
    cp = chroot("blender -b --factory-startup -P headless.py -- run --layers 0")
    assert cp.returncode == 2, (cp.returncode, cp.stderr)
    assert len(own_lines(cp.stderr)) == 1 and "layers" in cp.stderr, cp.stderr
