"""Batch jobs from Python: the same job files, work lists, outputs and manifests as
``hatchery batch`` (docs/batch.md), mapped over a Dask cluster when you give a client.

>>> from dask.distributed import Client, LocalCluster
>>> import hatchery.batch
>>> client = Client(LocalCluster(n_workers=4, threads_per_worker=1))
>>> hatchery.batch.run("jobs/default_turntable.ron", client, out="out/turntable")
{'rendered': 4, 'skipped': 0, 'failed': 0, 'complete': 4, 'problems': [], ...}

Each Dask task renders one chunk of the items (chunk k takes items k, k+K, k+2K, …, as
``--shard k/K``) in one session in its worker process, so a worker opens the GPU once per chunk
and its cache keeps what does not change from item to item. Tasks that die can be run again:
items already done are skipped.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional

from . import _hatchery
from ._hatchery import JobError  # noqa: F401  (re-exported)

PathLike = Any


def items(job: PathLike) -> List[Dict[str, Any]]:
    """The job's work list: ``{index, output, input, params, frame}`` per item, in order."""
    return _hatchery.batch_items(os.fspath(job))


def render_chunk(job: str, out: str, indices: List[int], tag: str) -> Dict[str, Any]:
    """Renders the items ``indices`` in this process (what one Dask task runs)."""
    return _hatchery.batch_run(job, out, list(indices), tag)


def merge(job: PathLike, out: PathLike) -> Dict[str, Any]:
    """Checks that every item is present once in the manifests and writes manifest.json."""
    return _hatchery.batch_merge(os.fspath(job), os.fspath(out))


def run(
    job: PathLike,
    client: Optional[Any] = None,
    out: Optional[PathLike] = None,
    chunks: Optional[int] = None,
) -> Dict[str, Any]:
    """Renders a job and merges its manifests; returns ``{rendered, skipped, failed, complete,
    problems, manifest}``.

    ``client``: a ``dask.distributed.Client``; its workers render ``chunks`` chunks (default:
    one per worker thread). Without one, this process renders every item. ``out``: the output
    folder (default: the job file's folder). Workers must see ``job`` and ``out`` at the same
    paths (a shared file system, as on a cluster). Raises JobError; failed items are counted
    and listed in ``problems``, not raised.
    """
    job = os.path.abspath(os.fspath(job))
    total = len(items(job))
    out = os.path.abspath(os.fspath(out)) if out is not None else os.path.dirname(job)
    if client is None:
        results = [render_chunk(job, out, list(range(total)), "0-of-1")]
    else:
        if chunks is None:
            threads = client.nthreads()
            chunks = max(1, sum(threads.values()) if threads else 1)
        chunks = max(1, min(int(chunks), total))
        parts = [list(range(k, total, chunks)) for k in range(chunks)]
        futures = client.map(
            render_chunk,
            [job] * chunks,
            [out] * chunks,
            parts,
            [f"dask-{k}-of-{chunks}" for k in range(chunks)],
            pure=False,
        )
        results = client.gather(futures)
    summary: Dict[str, Any] = {
        key: sum(r[key] for r in results) for key in ("rendered", "skipped", "failed")
    }
    summary["manifests"] = [os.fspath(r["manifest"]) for r in results]
    merged = merge(job, out)
    summary.update(complete=merged["complete"], problems=merged["problems"], manifest=merged["manifest"])
    return summary
