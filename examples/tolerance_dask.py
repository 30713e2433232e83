"""Runs a tolerance study's Monte Carlo in shards on a Dask cluster, then merges them.

Each shard is one `mechdraw run SCENE --shard K/N` (a deterministic share of the samples,
docs/tolerances.md); the workers of dask.distributed's LocalCluster run them in parallel and
`mechdraw merge` adds their partial statistics into exactly those of one run with the same
seed. The same submission works on a real cluster: replace LocalCluster by the scheduler's
address (every worker needs the mechdraw binary and the scene file).

    python3 -m venv /tmp/dask && /tmp/dask/bin/pip install "dask[distributed]"
    cargo build --release
    /tmp/dask/bin/python examples/tolerance_dask.py templates/fourbar-tolerances.toml 4 out/

Arguments: the scene, the number of shards N, the output directory; further arguments are
passed to every shard run (e.g. --set tolerances.settings.samples=1000000).
"""

import pathlib
import subprocess
import sys
import tempfile

from dask.distributed import Client, LocalCluster

MECHDRAW = pathlib.Path(__file__).resolve().parent.parent / "target" / "release" / "mechdraw"


def shard(scene: str, k: int, n: int, out: str, extra: list) -> str:
    """Runs shard k of n into `out`; returns the shard file's path."""
    done = subprocess.run(
        [str(MECHDRAW), "run", scene, "--shard", f"{k}/{n}", "--out", out, "-q", *extra],
        capture_output=True,
        text=True,
    )
    if done.returncode != 0:
        raise RuntimeError(f"shard {k}/{n}: {done.stderr.strip()}")
    found = sorted(pathlib.Path(out).glob(f"*-shard-{k}-of-{n}.json"))
    if len(found) != 1:
        raise RuntimeError(f"shard {k}/{n}: expected one shard file in {out}, found {found}")
    return str(found[0])


def main() -> None:
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    scene, n, out, extra = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
    with tempfile.TemporaryDirectory() as shards:
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=False) as cluster, Client(cluster) as client:
            futures = [client.submit(shard, scene, k, n, shards, extra, pure=False) for k in range(1, n + 1)]
            files = client.gather(futures)
        merged = subprocess.run([str(MECHDRAW), "merge", *files, "--out", out], capture_output=True, text=True)
        sys.stderr.write(merged.stderr)
        if merged.returncode != 0:
            sys.exit(merged.returncode)

if __name__ == "__main__":
    main()
