"""One self-contained HTML page: inline CSS, inline SVG figures, no external files, so a report
opens offline and can be mailed as one file. Figures are numbered in order; every figure has a
title and a caption line. A small inline script counts the figures that rendered (an <svg> with
a non-empty box and drawn paths) into <html data-figures-rendered=...> for the browser test."""

import datetime
import html

CSS = """
:root { --ink:#1d2330; --muted:#5b6475; --line:#d9dde5; --card:#f5f7fa; --accent:#1f5fa8; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff;
       font: 15px/1.45 "DejaVu Sans", "Liberation Sans", Arial, sans-serif; }
main { max-width: 1120px; margin: 0 auto; padding: 20px 28px 48px; }
h1 { font-size: 25px; margin: 6px 0 2px; }
h2 { font-size: 19px; margin: 34px 0 8px; padding-bottom: 4px; border-bottom: 2px solid var(--line); }
p.meta { color: var(--muted); margin: 0 0 14px; font-size: 13px; }
p.intro { margin: 6px 0 12px; }
.banner { border: 2px solid #b3261e; background: #fdecea; color: #5f1410; padding: 10px 14px;
          margin: 12px 0 16px; border-radius: 6px; }
.banner strong { letter-spacing: 0.04em; }
.cards { display: flex; flex-wrap: wrap; gap: 10px; margin: 12px 0 6px; }
.card { background: var(--card); border: 1px solid var(--line); border-radius: 8px; padding: 8px 12px; min-width: 150px; flex: 1 1 150px; }
.card .label { color: var(--muted); font-size: 12px; overflow-wrap: anywhere; text-transform: uppercase; letter-spacing: 0.03em; }
.card .value { font-size: 20px; font-weight: bold; overflow-wrap: anywhere; }
.card .note { color: var(--muted); font-size: 12px; }
.card.bad .value { color: #b3261e; }
.card.good .value { color: #1b6e3a; }
figure.report-figure { margin: 18px 0 22px; padding: 8px; border: 1px solid var(--line); border-radius: 8px; }
figure.report-figure svg { display: block; width: 100%; max-width: 100%; height: auto; margin: 0 auto; }
figcaption { color: var(--ink); font-size: 14px; margin: 6px 6px 2px; }
figcaption b { color: var(--accent); }
table { border-collapse: collapse; margin: 8px 0 6px; font-size: 13.5px; }
th, td { border-bottom: 1px solid var(--line); padding: 4px 10px; text-align: right; vertical-align: top; white-space: nowrap; }
th { background: var(--card); font-weight: bold; white-space: normal; }
td.text, th.text { text-align: left; }
td.wrap { white-space: normal; min-width: 240px; text-align: left; }
tr.bad td { background: #fdecea; }
p.tablecaption { color: var(--muted); font-size: 13px; margin: 2px 0 14px; }
ul.notes li { margin: 3px 0; }
.table-wrap { overflow-x: auto; }
code { font-size: 13px; }
"""

SELF_CHECK = """
(function () {
  var figures = document.querySelectorAll('figure.report-figure');
  var rendered = 0;
  figures.forEach(function (f) {
    var svg = f.querySelector('svg');
    if (!svg) return;
    var box = svg.getBoundingClientRect();
    if (box.width > 50 && box.height > 50 && svg.querySelectorAll('path').length > 0) rendered += 1;
  });
  document.documentElement.setAttribute('data-figures', String(figures.length));
  document.documentElement.setAttribute('data-figures-rendered', String(rendered));
})();
"""


def esc(text):
    return html.escape(str(text), quote=True)


class Page:
    """Collects the blocks of a report in order and renders the page."""

    def __init__(self, title, meta):
        self.title = title
        self.blocks = []
        self.figure_count = 0
        self.meta = meta

    def banner(self, text):
        self.blocks.append(f'<div class="banner" role="alert"><strong>REPRESENTATIVE DATA, NOT MEASUREMENTS.</strong> {esc(text)}</div>')

    def cards(self, items):
        """items: (label, value, note, tone) with tone '', 'good' or 'bad'."""
        out = ['<div class="cards">']
        for label, value, note, tone in items:
            out.append(f'<div class="card {tone}"><div class="label">{esc(label)}</div><div class="value">{esc(value)}</div>'
                       f'<div class="note">{esc(note)}</div></div>')
        out.append("</div>")
        self.blocks.append("".join(out))

    def section(self, title, intro=None):
        self.blocks.append(f"<h2>{esc(title)}</h2>")
        if intro:
            self.blocks.append(f'<p class="intro">{esc(intro)}</p>')

    def paragraph(self, text):
        self.blocks.append(f'<p class="intro">{esc(text)}</p>')

    def figure(self, svg, title, caption):
        self.figure_count += 1
        n = self.figure_count
        self.blocks.append(f'<figure class="report-figure" id="figure-{n}">{svg}'
                           f"<figcaption><b>Figure {n}. {esc(title)}.</b> {esc(caption)}</figcaption></figure>")

    def table(self, headers, rows, caption=None, text_columns=(0,), bad_rows=(), wrap_columns=()):
        """headers: column titles; rows: lists of cells (already formatted); text_columns are
        left-aligned; wrap_columns (long sentences) wrap; rows whose index is in bad_rows are
        highlighted."""
        cls = lambda k: ' class="wrap"' if k in wrap_columns else ' class="text"' if k in text_columns else ""
        out = ['<div class="table-wrap"><table><thead><tr>']
        out += [f"<th{cls(k)}>{esc(h)}</th>" for k, h in enumerate(headers)]
        out.append("</tr></thead><tbody>")
        for i, row in enumerate(rows):
            out.append('<tr class="bad">' if i in bad_rows else "<tr>")
            out += [f"<td{cls(k)}>{esc(c)}</td>" for k, c in enumerate(row)]
            out.append("</tr>")
        out.append("</tbody></table></div>")
        if caption:
            out.append(f'<p class="tablecaption">{esc(caption)}</p>')
        self.blocks.append("".join(out))

    def notes(self, items):
        if items:
            self.blocks.append('<ul class="notes">' + "".join(f"<li>{esc(t)}</li>" for t in items) + "</ul>")

    def render(self):
        stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
        return ("<!DOCTYPE html>\n"
                f'<html lang="en"><head><meta charset="utf-8">'
                f'<meta name="viewport" content="width=device-width, initial-scale=1">'
                f"<title>{esc(self.title)}</title><style>{CSS}</style></head>\n<body><main>\n"
                f"<h1>{esc(self.title)}</h1>\n<p class=\"meta\">{esc(self.meta)} &middot; report generated {stamp} by gradem</p>\n"
                + "\n".join(self.blocks)
                + f"\n</main><script>{SELF_CHECK}</script></body></html>\n")


SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def fmt(value, digits=4):
    """A number for people: `digits` significant digits, '–' when missing."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        return "–"
    if v != v or v in (float("inf"), float("-inf")):
        return "–"
    if v == 0:
        return "0"
    text = f"{v:.{digits}g}"
    if "e" in text and 1 <= abs(v) < 1e7:
        return f"{v:.0f}"  # e.g. a modulus in MPa: 11992, not 1.199×10⁴
    if "e" in text:
        mantissa, exponent = text.split("e")
        return f"{mantissa}×10{str(int(exponent)).translate(SUPERSCRIPT)}"
    return text


def fixed(value, decimals):
    """A number with a fixed number of decimals, '–' when missing."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        return "–"
    return "–" if v != v or v in (float("inf"), float("-inf")) else f"{v:.{decimals}f}"


def pct(value, digits=1, signed=True):
    try:
        v = float(value) * 100.0
    except (TypeError, ValueError):
        return "–"
    if v != v:
        return "–"
    return f"{v:+.{digits}f} %" if signed else f"{v:.{digits}f} %"
