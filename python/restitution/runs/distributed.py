"""Sweeps on a Dask distributed cluster: each chunk is one task calling the Rust engine.

Needs ``pip install "restitution[dask]"`` (dask.distributed) here and the same version of
restitution on every worker. The spec is sent to the workers once; a task generates its own
cases from the chunk's case range, runs them and returns the rows; this process writes each
chunk file as its task finishes (so the workers need no shared file system). Rows are the local
run's: a case runs the same code on any machine, and the files are keyed by chunk index.
"""

from __future__ import annotations

import uuid
from typing import Any, Callable, Sequence

import polars as pl

from .._core import __version__ as ENGINE_VERSION
from .sweep import Chunk, SweepSpec


def _chunk_task(spec: SweepSpec, start: int, stop: int, threads: int, version: str) -> pl.DataFrame:
    if ENGINE_VERSION != version:
        raise RuntimeError(f"worker runs restitution {ENGINE_VERSION}, the client {version}: "
                           "install the same version on every worker")
    return spec.run(start, stop, threads)


def get_client(scheduler: Any) -> tuple[Any, bool]:
    """(client, whether we own it): a ``distributed.Client`` as is, or a new one for an address."""
    try:
        from distributed import Client
    except ImportError:
        raise ImportError('a Dask scheduler needs dask.distributed: pip install "restitution[dask]"') from None
    if isinstance(scheduler, Client):
        return scheduler, False
    if not isinstance(scheduler, str):
        raise TypeError(f"`scheduler` must be an address (str) or a distributed.Client (found {type(scheduler).__name__})")
    return Client(scheduler), True


def run_chunks(spec: SweepSpec, chunks: Sequence[Chunk], scheduler: Any, threads: int,
               finished: Callable[[Chunk, pl.DataFrame], None], stopped: Callable[[], bool]) -> None:
    """Runs ``chunks`` as Dask tasks and calls ``finished(chunk, rows)`` here as each completes.

    A bounded number of tasks is in flight (twice the cluster's worker threads), so neither the
    scheduler nor this process ever holds the whole sweep. ``threads`` = 0 lets each task use
    its worker's shared engine thread pool (all cores) without oversubscribing it. When
    ``stopped()`` turns true, the tasks not yet finished are cancelled.
    """
    if not chunks:
        return
    from distributed import as_completed

    client, owned = get_client(scheduler)
    live: dict[str, tuple[Any, Chunk]] = {}
    try:
        window = max(2, 2 * sum(client.nthreads().values()))
        spec_future = client.scatter(spec, broadcast=True, hash=False)
        run_id = uuid.uuid4().hex[:12]
        todo = iter(chunks)
        running = as_completed()

        def submit_next() -> None:
            c = next(todo, None)
            if c is None:
                return
            fut = client.submit(_chunk_task, spec_future, c.start, c.stop, threads, ENGINE_VERSION,
                                key=f"restitution-chunk-{run_id}-{c.index}", pure=False)
            live[fut.key] = (fut, c)
            running.add(fut)

        for _ in range(window):
            submit_next()
        for fut in running:
            _, c = live.pop(fut.key)
            frame = fut.result()  # a task's error is raised here, naming the case
            fut.release()
            finished(c, frame)
            if stopped():
                break
            submit_next()
    finally:
        for fut, _ in live.values():  # stopped or failed: the rest is not wanted
            fut.cancel()
        if owned:
            client.close()


__all__ = ["get_client", "run_chunks"]
