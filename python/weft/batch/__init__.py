"""Batch BTF fitting and batch rendering, on one machine or a Ray cluster (issue 16).

    import weft.batch as wb
    jobs = wb.make_jobs(["wool.zip", "denim/"], tiles=4)          # BTF datasets
    with wb.executor("ray") as ex:                                # local Ray cluster
        wb.fit_btf_batch(jobs, "out/btf", ex)                    # = btf fit per dataset
    with wb.executor("ray", address="head:6379") as ex:           # an existing cluster
        wb.render_batch(wb.load_render_jobs("jobs.json"), "out/frames", ex)
    with wb.executor("serial") as ex:                             # no Ray at all, same bytes
        ...

Modules: :mod:`~weft.batch.executor` (serial and Ray executors, actor pools),
:mod:`~weft.batch.cluster` (connecting), :mod:`~weft.batch.manifest` (JSON manifest, resume),
:mod:`~weft.batch.btf_stages` / :mod:`~weft.batch.btf_batch` (BTF fits split by bands of texels
or by views), :mod:`~weft.batch.render_jobs` / :mod:`~weft.batch.render_worker` /
:mod:`~weft.batch.render_batch` (frames as tasks on workers that keep one renderer each),
:mod:`~weft.batch.cli` (``python -m weft batch``). See docs/batch.md.
"""

from weft.batch.btf_batch import dataset_views, fit_btf_batch, make_jobs
from weft.batch.btf_stages import BtfJob
from weft.batch.cluster import executor

__all__ = ["BtfJob", "dataset_views", "executor", "fit_btf_batch", "make_jobs"]
from weft.batch.render_batch import render_batch  # noqa: E402
from weft.batch.render_jobs import RenderJob, load_render_jobs, make_render_job  # noqa: E402

__all__ += ["RenderJob", "load_render_jobs", "make_render_job", "render_batch"]
