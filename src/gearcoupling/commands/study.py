"""``gearcoupling study FILE``: a design study on dask.distributed -> Parquet table + plots."""

from __future__ import annotations

from pathlib import Path

from ..io import default_output_dir, write_json
from ..plots import save_figure
from ..study import (
    MAX_WORKERS,
    chunks,
    compare_curves,
    load_study,
    optimise_crown,
    optimise_options,
    plot_capacity_curves,
    plot_k_histogram,
    read_table,
    run_study,
    scheduler_address,
    study_plots,
    summarise_rows,
    write_rows,
)
from .common import count, number_in, progress, writing_into
from .folders import claim, holds_folders


def register(sub) -> None:
    p = sub.add_parser("study", help="design study over sampled spec keys and conditions on "
                       "dask.distributed (Parquet table, plots; resumable)")
    p.add_argument("file", metavar="FILE", help="study TOML file, or a bundled study name")
    p.add_argument("-o", "--output", metavar="DIR", default=None,
                   help="output folder (default: outputs/study-<name>)")
    p.add_argument("--scheduler", metavar="tcp://HOST:PORT", default=None,
                   help="use a running dask scheduler instead of a local cluster")
    p.add_argument("--connect-timeout", type=number_in(0.0, 3600.0, "s", open_lo=True),
                   default=10.0, metavar="S", help="seconds to wait for --scheduler before "
                   "giving up, in (0, 3600] (default 10)")
    p.add_argument("--workers", type=count(1, MAX_WORKERS), default=None, metavar="N",
                   help=f"local cluster worker processes, 1-{MAX_WORKERS} "
                   "(default: one per core)")
    p.add_argument("--fresh", action="store_true",
                   help="discard finished chunks in the output folder and start over")
    p.add_argument("--no-plots", action="store_true", help="write only the table")
    p.set_defaults(func=run)


@holds_folders
def run(args) -> int:
    study = load_study(args.file)
    if args.scheduler is not None:
        scheduler_address(args.scheduler, "--scheduler")
    out = claim(writing_into(default_output_dir(f"study-{study.name}") if args.output is None
                             else args.output))
    if study.optimise is not None:
        return _optimise(study, out, plots=not args.no_plots)

    with progress(f"study {study.name} (chunks)", len(chunks(study))) as update:
        result = run_study(study, out, scheduler=args.scheduler, workers=args.workers,
                           connect_timeout_s=args.connect_timeout, fresh=args.fresh,
                           progress=update)
    if result.skipped_chunks:
        print(f"resuming: {result.skipped_chunks} finished chunk(s) in {out / 'parts'} skipped, "
              f"{result.chunks - result.skipped_chunks} to run")
    print(result.table)
    if result.failed_rows:
        print(f"{result.failed_rows} of {result.rows} rows refused (see the 'error' column)")
    rows = read_table(result.table) if study.tolerances or study.plots else []
    if study.tolerances:
        _tolerance_summary(study, rows, out, plots=not args.no_plots)
    if not args.no_plots and study.plots:
        for path in study_plots(study, rows, out):
            print(path)
    return 0


def _tolerance_summary(study, rows, out: Path, *, plots: bool) -> None:
    summary = summarise_rows(study, rows)
    print(write_json(out / "tolerance_summary.json", summary))
    for s in summary:
        print(f"K = {s['K_mean']:.4f} [{s['K_mean_low']:.4f}, {s['K_mean_high']:.4f}] "
              f"({100 * s['confidence']:g} % bounds of the mean), 5th percentile "
              f"{s['K_p05']:.4f}, {s['samples']} samples; {s['samples_needed']} needed for "
              f"+-{s['precision']:g}")
    if plots and len(summary) == 1:
        print(save_figure(plot_k_histogram(rows, summary[0]), out / "K-histogram.png"))


def _optimise(study, out: Path, *, plots: bool) -> int:
    """Crown optimisation: every evaluation's row, the optimum, capacity curves against the
    compared specs."""
    options = optimise_options(study)
    n = options["max_evaluations"]
    with progress(f"optimise {study.name} (evaluations)", n) as update:
        seen = [0]

        def on_row(_row) -> None:
            seen[0] += 1
            update(min(seen[0], n), n)

        result = optimise_crown(study, on_row=on_row)
    write_rows(result.rows, out / "study.parquet")
    print(out / "study.parquet")
    if result.best is None:
        print("no feasible crown found within the bounds and budget")
        return 1
    keys = [q.key for q in study.parameters]
    print("optimum: " + ", ".join(f"{k} = {result.best[k]:.6g}" for k in keys)
          + (f"; wear life {result.best['objective']:.4g} h at "
             f"{max(options['angles_deg']):g}°" if options["objective"] == "wear_life_h" else
             f"; capacity {options['objective']} {result.best['objective']:.1f} N m")
          + ", critical "
          f"misalignment {result.best['critical_misalignment_deg']}")
    curves = compare_curves(study, result.best)
    report = {"best": result.best, "evaluations": len(result.rows),
              "capacity_curves_Nm": {n: dict(zip([f"{a:g}" for a in angles], c.tolist(),
                                                 strict=True))
                                     for n, (angles, c) in curves.items()}}
    print(write_json(out / "optimum.json", report))
    for name, (_, cap) in curves.items():
        print(f"  {name:28s} " + " ".join(f"{c:8.0f}" for c in cap) + "  N m")
    if plots:
        print(save_figure(plot_capacity_curves(curves), out / "capacity-curves.png"))
    return 0
