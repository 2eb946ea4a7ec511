"""The scaling plot: optimize's time and peak memory against N, drawn by gnuplot."""
import os
import shutil
import tempfile

import analysis
import process
from scenarios import FRAME_RATE_HZ

# variant, legend, colour (the same in both panels), line width: drift's is
# wider so that it still shows where the loop-closed line covers it.
SERIES = (("drift", "open-loop drift", "#1f77b4", 4), ("loop", "loop-closed", "#d62728", 1.5))


def _series_rows(records, summaries, variant):
    """'N seconds GiB floor_seconds' rows of the HDL-32 scenarios of one variant, by N."""
    rows = sorted((record["frames"], summaries[name]) for name, record in records.items()
                  if record["sensor"] == "hdl32" and record["variant"] == variant)
    return [f"{n} {s['wall_s']:.3f} {s['peak_rss_mib'] / 1024:.4f} {s['floor_s']:.3f}"
            for n, s in rows]


def _script(records, summaries, png):
    blocks, time_plots, memory_plots = [], [], []
    for variant, title, colour, width in SERIES:
        rows = _series_rows(records, summaries, variant)
        if not rows:
            continue
        blocks.append(f"${variant} << EOD\n" + "\n".join(rows) + "\nEOD")
        style = f"with linespoints lw {width} pt 7 lc '{colour}' title '{title}'"
        time_plots.append(f"${variant} using 1:2 {style}")
        memory_plots.append(f"${variant} using 1:3 {style}")
    if _series_rows(records, summaries, "drift"):  # the floor is drawn for the drift datasets
        time_plots.append("$drift using 1:4 with linespoints dt 2 pt 6 lc 'gray40' "
                          "title 'I/O floor (read + downsample)'")
    budget = analysis.TIME_BUDGET_FRACTION / FRAME_RATE_HZ
    time_plots.append(f"{budget} * x with lines dt 3 lc 'black' title 'target: 5 % of duration'")
    memory_plots.append(f"{analysis.MEMORY_TARGET_MIB / 1024} with lines dt 3 lc 'black' title 'target: 4 GiB'")
    return "\n".join([
        *blocks,
        "set terminal png size 1200,480 font ',10'",
        f"set output '{png}'",
        "set multiplot layout 1,2 title 'hba optimize on simulated HDL-32 sequences (10 Hz)'",
        "set grid", "set key top left", "set xlabel 'frames N'", "set xrange [0:*]", "set yrange [0:*]",
        "set ylabel 'wall time (s)'",
        "plot " + ", ".join(time_plots),
        "set ylabel 'peak RSS (GiB)'",
        "plot " + ", ".join(memory_plots),
        "unset multiplot",
    ]) + "\n"


def draw(records, summaries, png):
    """Writes png; returns False (drawing nothing) when gnuplot is not installed."""
    if shutil.which("gnuplot") is None:
        return False
    png.parent.mkdir(parents=True, exist_ok=True)
    partial = png.with_name(png.name + ".partial")
    with tempfile.NamedTemporaryFile("w", suffix=".gp") as script:
        script.write(_script(records, summaries, partial))
        script.flush()
        process.run(["gnuplot", script.name])
    os.replace(partial, png)  # a killed run never leaves half a picture
    return True
