"""Figure options shared by every plot function and command: size, footer, title, format.

    with style.using(width="column", footer=False):
        plot_run.plot_map(run, "rt_St.pdf", **dict(plot_run.MAPS)["rt_St.png"])

The command lines set them from --size, --no-footer, --title and --format
(add_cli_options, from_cli). A plot function given `ax=` draws into that axes and leaves
the figure's size, footer and saving to the caller.
"""
import argparse
import contextlib
import os

import matplotlib
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

# Text widths [in] of the usual journals' columns and pages (A&A, MNRAS, ApJ: 3.3-3.5 in
# columns, 6.9-7.3 in pages): figures made at that size need no scaling in LaTeX.
WIDTHS = {"default": None, "column": 3.5, "page": 7.1}
FORMATS = ("png", "pdf", "svg")
_options = {"width": None, "footer": True, "title": None, "format": "png"}
# fonts of a column-width figure (rcParams font.size): legible at 1:1 in a paper
COLUMN_FONT_SIZE = 7.0


def options():
    """The current options: width [in] (None: each figure's own), footer (bool), title
    (None: each figure's own), format ("png", "pdf", "svg")."""
    return dict(_options)


@contextlib.contextmanager
def using(width=None, footer=None, title=None, format=None):
    """Set options for the figures made inside the block. width: "column", "page",
    "default" or inches (float)."""
    saved = dict(_options)
    if width is not None:
        _options["width"] = WIDTHS.get(width, width) if isinstance(width, str) else float(width)
    if footer is not None:
        _options["footer"] = bool(footer)
    if title is not None:
        _options["title"] = title
    if format is not None:
        if format not in FORMATS:
            raise ValueError(f"format {format!r}: one of {', '.join(FORMATS)}")
        _options["format"] = format
    rc = {"font.size": COLUMN_FONT_SIZE} if narrow() else {}
    try:
        with matplotlib.rc_context(rc):
            yield dict(_options)
    finally:
        _options.clear()
        _options.update(saved)


def narrow():
    """True when the chosen width is under 5 in (a column): fewer legend columns."""
    return bool(_options["width"]) and _options["width"] < 5.0


def new_figure(width, height, **kwargs):
    """An Agg-backed Figure of the given size [in], at the chosen width; the height
    scales as the square root of the width's ratio (a narrow figure keeps room for its
    legend and labels)."""
    chosen = _options["width"]
    if chosen:
        width, height = chosen, height * (chosen / width) ** 0.5
    fig = Figure(figsize=(width, height), dpi=150, layout="constrained", **kwargs)
    FigureCanvasAgg(fig)
    return fig


def title(default):
    """The figure's title: the --title given, else the figure's own."""
    return default if _options["title"] is None else _options["title"]


def footer(fig, text):
    """The provenance footer (grey, bottom right) unless --no-footer."""
    if _options["footer"] and text:
        fig.text(0.995, 0.002, text, ha="right", va="bottom", fontsize=6, color="0.5")


def savefig(fig, path, **kwargs):
    """fig.savefig(path) (the format from the path's extension)."""
    fig.savefig(path, **kwargs)


def file_name(name):
    """'sigma_d.png' with the chosen format's extension ('sigma_d.pdf')."""
    return os.path.splitext(name)[0] + "." + _options["format"]


def add_cli_options(parser):
    """--format, --no-footer, --title, --size on an argparse parser."""
    parser.add_argument("--format", choices=FORMATS, default="png",
                        help="file format of the figures (default png)")
    parser.add_argument("--no-footer", action="store_true",
                        help="leave out the provenance footer (file, version, commit)")
    parser.add_argument("--title", help="title of every figure, in place of its own "
                                        "('' for none)")
    parser.add_argument("--size", default="default",
                        help="figure width: column (3.5 in, fonts 7 pt), page (7.1 in), "
                             "or inches (default: each figure's own)")


def cli_parser(doc, source, source_help, outdir_help):
    """The parser of a plotting command: description `doc`, the positional `source` and
    -o/--outdir; the caller adds its own options, then calls run_cli."""
    parser = argparse.ArgumentParser(description=doc,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument(source, help=source_help)
    parser.add_argument("-o", "--outdir", help=outdir_help)
    return parser


def run_cli(parser, argv, body):
    """Parse `argv` with the style options added and return body(args), run inside them."""
    add_cli_options(parser)
    args = parser.parse_args(argv)
    with from_cli(args):
        return body(args)


def from_cli(args):
    """The using(...) context of parsed --format/--no-footer/--title/--size."""
    size = args.size
    if size not in WIDTHS:
        try:
            size = float(size)
        except ValueError:
            raise SystemExit(f"--size {size}: column, page, default or a width in inches")
    return using(width=size, footer=not args.no_footer, title=args.title, format=args.format)
