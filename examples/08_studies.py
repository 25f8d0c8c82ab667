"""A design study on dask.distributed (a local cluster starts and stops by itself).

Run: python examples/08_studies.py
"""

import gearcoupling as gc


def main() -> None:
    study: gc.Study = gc.load_study("wei-fig14")
    run: gc.StudyRun = gc.run_study(study, "outputs/examples/study", workers=2, fresh=True)
    print(run.rows, "rows in", run.table)


if __name__ == "__main__":  # dask starts worker processes that import this file
    main()
