"""hodr's ask/tell on a Dask cluster: each batch Auto asks for is scattered over the
cluster's workers, for objectives too slow for one machine (a renderer at full
resolution).

    pip install ./python "dask[distributed]"
    python python/examples/dask_ask_tell.py                      # a local cluster
    python python/examples/dask_ask_tell.py tcp://scheduler:8786  # an existing one

The objective here is a stand-in for a render: a rounded (plateau) quadratic that
sleeps a little, as a render would take time. Replace `render_loss` with yours; it must
be importable by the workers (defined in a module, not typed into a notebook cell, or
shipped with `client.upload_file`).
"""

import sys
import time

import numpy as np
from dask.distributed import Client, LocalCluster

import hodr

TARGET = np.array([1.3, -0.4, 2.2])


def render_loss(x, seconds=0.01):
    """A slow objective with plateaus: the squared distance of coordinates rounded to
    quarters from TARGET (least value 0.015, off the grid)."""
    time.sleep(seconds)
    return float(np.sum((np.round(4.0 * x) / 4.0 - TARGET) ** 2))


def optimise(client, x0, sigma0=1.0, budget=600, seed=0, seconds=0.01):
    """Auto with every batch evaluated on `client`'s workers; the OptimizeResult."""
    opt = hodr.Optimizer(x0, sigma0, budget=budget, seed=seed)
    while not opt.stop():
        X = opt.ask()
        futures = client.map(render_loss, list(X), seconds=seconds, pure=False)
        opt.tell(client.gather(futures))
    return opt.result


def main():
    if len(sys.argv) > 1:
        client = Client(sys.argv[1])
    else:
        client = Client(LocalCluster(n_workers=2, threads_per_worker=1))
    with client:
        start = time.perf_counter()
        res = optimise(client, x0=[-2.0, 3.0, 0.0])
        elapsed = time.perf_counter() - start
    print(f"x = {res.x}, f = {res.fun:.4g}, {res.nfev} evaluations in {elapsed:.1f} s")
    print(res.message)


if __name__ == "__main__":
    main()
