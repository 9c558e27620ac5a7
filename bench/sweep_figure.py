"""What sweep plots share: matplotlib without a display, and a footer that says when the
figure was made and the exact command that made it (and, given, the run that made its data), so
a PNG in docs/ can be redone. Scripts under bench/ put bench/ on sys.path and import it.
"""
import datetime
import os
import shlex
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (callers draw with it)


def command_line():
    """This process's command, with ZONESIM_BIN in front when it was set."""
    words = [sys.executable] + sys.argv
    line = " ".join(shlex.quote(w) for w in words)
    if "ZONESIM_BIN" in os.environ:
        line = f"ZONESIM_BIN={shlex.quote(os.environ['ZONESIM_BIN'])} {line}"
    return line


def save(fig, path, note=""):
    """Stamps the date, time and command under the axes, writes `path` and closes `fig`."""
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    footer = f"{now}: {command_line()}" + (f"  ({note})" if note else "")
    width = int(fig.get_figwidth() * 17)  # characters of 7-point text across the figure
    lines = textwrap.wrap(footer, width, break_on_hyphens=False)
    fig.text(0.01, 0.01, "\n".join(lines), fontsize=7, color="0.35", ha="left", va="bottom")
    fig.tight_layout(rect=(0, 0.02 + 0.03 * len(lines), 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}", file=sys.stderr)
