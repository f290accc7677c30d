"""hatchery.batch: the reference job mapped over a Dask LocalCluster of 2 worker processes
writes what the command line writes, byte for byte."""

import subprocess

import pytest

import hatchery
import hatchery.batch


def test_dask_local_cluster_renders_the_reference_job_as_the_cli(repo, tmp_path, hatchery_bin):
    distributed = pytest.importorskip("distributed", reason="dask.distributed (pip install 'dask[distributed]')")
    job = repo / "jobs" / "default_turntable.ron"
    local = tmp_path / "local"
    subprocess.run([hatchery_bin, "batch", job, "--out", local], check=True, capture_output=True)

    items = hatchery.batch.items(job)
    assert [i["output"] for i in items] == [f"frame_{k:04}.png" for k in range(4)]
    assert items[1]["params"] == {"camera.azimuth": "90"}

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        summary = hatchery.batch.run(job, client, out=tmp_path / "dask")
    assert summary["rendered"] == 4 and summary["failed"] == 0, summary
    assert summary["complete"] == 4 and summary["problems"] == [], summary
    assert len(summary["manifests"]) == 2
    for k in range(4):
        name = f"frame_{k:04}.png"
        assert (tmp_path / "dask" / name).read_bytes() == (local / name).read_bytes(), name

    # Run again: everything is done already.
    again = hatchery.batch.run(job, out=tmp_path / "dask")
    assert again["skipped"] == 4 and again["rendered"] == 0


def test_bad_jobs_raise_job_error(tmp_path):
    bad = tmp_path / "job.ron"
    bad.write_text('(graph: "g.ron", size: (8, 8), output: "x_{colour}.png")')
    with pytest.raises(hatchery.JobError) as caught:
        hatchery.batch.items(bad)
    assert "unknown placeholder `{colour}`" in str(caught.value) and "job.ron" in str(caught.value)
    missing = tmp_path / "job2.ron"
    missing.write_text('(graph: "nowhere.ron", size: (8, 8), output: "x.png")')
    with pytest.raises(hatchery.JobError) as caught:
        hatchery.batch.run(missing, out=tmp_path / "o")
    assert "nowhere.ron" in str(caught.value)
