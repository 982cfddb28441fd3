"""The report as one self-contained HTML file (figures embedded) and as Markdown (figures beside it)."""

from __future__ import annotations

import base64
import html
import json
from pathlib import Path
from typing import Any

from ..models import model_title
from .registry import ThesisItem, chapter_title, rows_of

__all__ = ["summary_rows", "write_report"]

_CSS = """body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;margin-top:2em}h3{margin-top:1.6em}
table{border-collapse:collapse;margin:.6em 0;font-size:.9em}td,th{border:1px solid #ccc;padding:3px 7px;
text-align:left;vertical-align:top}th{background:#f3f3f3}img{max-width:100%;border:1px solid #eee}
.agrees{color:#176e2a}.disagrees{color:#b3261e}.info{color:#555}.pending{color:#8a6d00}
code,pre{background:#f6f6f6;font-size:.85em}pre{padding:.5em;overflow-x:auto}.cap{color:#444}"""


def _model_rows(it: ThesisItem, results: dict[tuple[str, str], dict[str, Any]]) -> list[dict[str, Any]]:
    """One entry per model shown for the item: status and the result holding its figures."""
    out: list[dict[str, Any]] = []
    for model, spec in rows_of(it):
        if spec is None:
            out.append({"model": model, "status": "pending", "result": None})
        elif spec.startswith("="):
            first = results.get((it.key, spec[1:]))
            status = "in the " + model_title(spec[1:]) + " row" if first else "not run"
            out.append({"model": model, "status": status, "result": None})
        else:
            r = results.get((it.key, model))
            out.append({"model": model, "status": "not run" if r is None else r["status"], "result": r})
    return out


#: the chapter table quotes whole findings up to about this many characters, then says how many more
SUMMARY_CHARS = 400


def summary_rows(
    items: list[ThesisItem], results: dict[tuple[str, str], dict[str, Any]]
) -> list[dict[str, Any]]:
    """The chapter-by-chapter table: item, models (with status), agrees? (with the count of verdicts) and
    the numbers: whole findings, the disagreeing ones first, never cut inside a finding."""
    rows = []
    for it in items:
        models, findings = [], []
        for m in _model_rows(it, results):
            models.append(f"{model_title(m['model'])} ({m['status']})")
            if m["result"] and m["result"].get("status") == "ran":
                findings += m["result"]["findings"]
        judged = [f for f in findings if f["verdict"] != "info"]
        n_agree = sum(f["verdict"] == "agrees" for f in judged)
        if not findings:
            agrees = "not run"
        elif not judged:
            agrees = "-"
        else:
            word = "yes" if n_agree == len(judged) else "no" if n_agree == 0 else "partly"
            agrees = f"{word} ({n_agree} of {len(judged)})"
        ordered = sorted(judged, key=lambda f: f["verdict"] != "disagrees")  # stable: disagreeing first
        quoted: list[str] = []
        for f in ordered:
            if quoted and sum(len(q) + 2 for q in quoted) + len(f["text"]) > SUMMARY_CHARS:
                break
            quoted.append(f["text"])
        numbers = "; ".join(quoted)
        if len(quoted) < len(ordered):
            numbers += f"; {len(ordered) - len(quoted)} more under the item"
        rows.append(
            {
                "chapter": it.chapter,
                "item": it.label,
                "key": it.key,
                "models": ", ".join(models),
                "agrees": agrees,
                "numbers": numbers or "-",
            }
        )
    return rows


def _table_html(rows: list[dict[str, Any]]) -> str:
    if not rows:
        return ""
    keys: list[str] = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    head = "".join(f"<th>{html.escape(k)}</th>" for k in keys)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(_cell(r.get(k)))}</td>" for k in keys) + "</tr>" for r in rows
    )
    return f"<table><tr>{head}</tr>{body}</table>"


def _table_md(rows: list[dict[str, Any]]) -> str:
    if not rows:
        return ""
    keys: list[str] = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    lines = ["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
    lines += ["| " + " | ".join(_cell(r.get(k)).replace("|", "/") for k in keys) + " |" for r in rows]
    return "\n".join(lines) + "\n"


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def _bytes_writer(data: bytes) -> Any:
    def write(tmp: str) -> None:
        Path(tmp).write_bytes(data)

    return write


def write_report(
    folder: Path, run: Any, *, quick: bool, versions: dict[str, str], scheduler: str
) -> list[Path]:
    """Write ``report.html``, ``report.md`` and ``figures/*.png`` into ``folder`` (atomically, through
    the current output set when there is one). Returns the paths."""
    from ..io import atomic_write, atomic_write_text

    items, results = run.items, run.results
    summary = summary_rows(items, results)
    row_time = sum(r.get("wall_time_s", 0.0) for r in results.values())
    settings = {
        "quick": quick,
        "scheduler": scheduler,
        "rows run now": run.ran,
        "rows reused from cache": run.reused,
        "wall time of this run [s]": round(run.wall_time_s, 2),
        "sum of row wall times [s]": round(row_time, 2),
    }
    title = "terradyn: the thesis reproduced (S. Agarwal, MIT MS thesis 2019)"
    h = [
        f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>",
        f"<style>{_CSS}</style></head><body><h1>{html.escape(title)}</h1>",
        "<p>Each item stands beside the thesis figure or table it reproduces. Every number below is "
        "computed by this run; 'agrees' compares with the cited reference or the model's own invariant. "
        "Thesis numbers that could not be checked are given as the section.</p>",
        "<h2>Settings and versions</h2>",
        _table_html([settings]),
        _table_html([versions]),
        "<h2>Chapter by chapter</h2>",
        _table_html(summary),
    ]
    md = [
        f"# {title}\n",
        "Each item stands beside the thesis figure or table it reproduces; every number is "
        "computed by this run.\n",
        "## Settings and versions\n",
        _table_md([settings]),
        _table_md([versions]),
        "## Chapter by chapter\n",
        _table_md(summary),
    ]
    files: list[Path] = []
    references: list[str] = []
    (folder / "figures").mkdir(parents=True, exist_ok=True)
    for chapter in dict.fromkeys(it.chapter for it in items):
        h.append(f"<h2>Chapter {chapter}: {html.escape(chapter_title(chapter))}</h2>")
        md.append(f"## Chapter {chapter}: {chapter_title(chapter)}\n")
        for it in (i for i in items if i.chapter == chapter):
            references += [r for r in it.references if r not in references]
            h.append(f"<h3 id='{it.key}'>{html.escape(it.label)}: {html.escape(it.caption)}</h3>")
            h.append(f"<p class='cap'>reproduced by <code>{html.escape(it.study)}</code></p>")
            md.append(f"### {it.label}: {it.caption}\n\nreproduced by `{it.study}`\n")
            for m in _model_rows(it, results):
                name = model_title(m["model"])
                r = m["result"]
                if r is None or r.get("status") != "ran":
                    why = r["error"] if r and r.get("error") else m["status"]
                    css = "pending" if m["status"] == "pending" else "info"
                    h.append(f"<p class='{css}'><b>{html.escape(name)}</b>: {html.escape(why)}</p>")
                    md.append(f"- **{name}**: {why}\n")
                    continue
                h.append(f"<p><b>{html.escape(name)}</b> ({r['wall_time_s']:.2f} s)</p>")
                md.append(f"**{name}** ({r['wall_time_s']:.2f} s)\n")
                for fig_name, png in r["figures"].items():
                    h.append(
                        f"<img alt='{html.escape(it.label)} {html.escape(fig_name)}' "
                        f"src='data:image/png;base64,{png}'>"
                    )
                    path = folder / "figures" / f"{it.key}__{m['model']}__{fig_name}.png"
                    files.append(atomic_write(path, _bytes_writer(base64.b64decode(png)), suffix=".png"))
                    md.append(f"![{it.label} {fig_name}](figures/{path.name})\n")
                h.append(
                    "<ul>"
                    + "".join(
                        f"<li class='{f['verdict']}'>[{f['verdict']}] {html.escape(f['text'])}</li>"
                        for f in r["findings"]
                    )
                    + "</ul>"
                )
                md += [f"- [{f['verdict']}] {f['text']}" for f in r["findings"]]
                md.append("")
                for tname, rows in r.get("tables", {}).items():
                    h.append(f"<p>{html.escape(tname)}</p>" + _table_html(rows))
                    md.append(f"{tname}:\n\n" + _table_md(rows))
                text = json.dumps(r["settings"], sort_keys=True)
                h.append(f"<details><summary>settings</summary><pre>{html.escape(text)}</pre></details>")
                md.append(f"settings: `{text}`\n")
    h.append("<h2>References</h2><ol>" + "".join(f"<li>{html.escape(r)}</li>" for r in references) + "</ol>")
    md.append("## References\n\n" + "\n".join(f"{i}. {r}" for i, r in enumerate(references, 1)) + "\n")
    h.append("</body></html>")
    files.append(atomic_write_text(folder / "report.html", "\n".join(h)))
    files.append(atomic_write_text(folder / "report.md", "\n".join(md)))
    return files
