"""How long --movie takes beside the bake it shows: the default model, .mp4 and .gif, a few steps.

    .venv/bin/python bench/movie.py [--size 640x360] [--steps 5,10]

Each case is one `headless.py run` (its own process); the times are the run's own JSON timings
(bake) and the movie's `seconds` (rendering and joining the frames). Absolute seconds are noisy
on a shared machine: compare per-frame costs and ratios from the same run of this script.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]


def one(fmt: str, step: int, size: str, folder: pathlib.Path) -> dict:
    movie, result = folder / f"m{step}.{fmt}", folder / f"r{step}{fmt}.json"
    done = subprocess.run([sys.executable, str(ROOT / "headless.py"), "run", "--quiet",
                           "--movie", str(movie), "--movie-step", str(step), "--render-size", size,
                           "--json", str(result)], capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(done.stderr)
    r = json.loads(result.read_text())
    m = r["movie"]
    return {"format": fmt, "step": step, "frames": len(m["frames"]), "bake_s": r["timings_s"]["bake"],
            "movie_s": m["seconds"], "per_frame_s": m["seconds"] / len(m["frames"]),
            "bytes": movie.stat().st_size}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", default="640x360")
    ap.add_argument("--steps", default="5,10")
    args = ap.parse_args()
    print("| format | step | frames | bake s | movie s | per frame s | movie / bake | size |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for fmt in ("mp4", "gif"):
            for step in (int(s) for s in args.steps.split(",")):
                c = one(fmt, step, args.size, pathlib.Path(tmp))
                print(f"| {c['format']} | {c['step']} | {c['frames']} | {c['bake_s']:.1f} | "
                      f"{c['movie_s']:.1f} | {c['per_frame_s']:.2f} | "
                      f"{c['movie_s'] / c['bake_s']:.0f}x | {c['bytes'] / 1e3:.0f} kB |",
                      flush=True)


if __name__ == "__main__":
    main()
