"""Shared by the chart scripts: matplotlib without a display, and where a chart's
CSV and PNG go (bench/out/, the PNG also to docs/images/ for docs/results.md)."""
import csv
import os
import shutil

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCS_IMAGES = os.path.join(ROOT, "docs", "images")


def pyplot():
    """matplotlib.pyplot on the Agg backend (no display needed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def write_csv(path, header, rows):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    print(f"csv: {path}", flush=True)


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def save_chart(fig, out_dir, name, docs=True):
    """Writes <out_dir>/<name>.png and, if `docs`, copies it to docs/images/<name>.png."""
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, name + ".png")
    fig.savefig(path, dpi=110)
    print(f"chart: {path}", flush=True)
    if docs:
        os.makedirs(DOCS_IMAGES, exist_ok=True)
        shutil.copyfile(path, os.path.join(DOCS_IMAGES, name + ".png"))
