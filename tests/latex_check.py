"""Test support: compile BibTeX entries with pdflatex and bibtex (the real TeX tools)."""

from __future__ import annotations

import subprocess
from pathlib import Path


def compile_latex(tmp_path: Path, bib: str, keys: list[str]) -> str:
    """pdflatex + bibtex + pdflatex on a document citing ``keys``; return the log (fails loudly)."""
    (tmp_path / "figs.bib").write_text(bib, encoding="utf-8")
    (tmp_path / "doc.tex").write_text(
        "\\documentclass{article}\n\\usepackage[T1]{fontenc}\n\\usepackage{url}\n"
        "\\begin{document}\nFigures \\cite{" + ",".join(keys) + "}.\n"
        "\\bibliographystyle{plain}\n\\bibliography{figs}\n\\end{document}\n", encoding="utf-8")
    run = dict(cwd=tmp_path, capture_output=True, text=True, timeout=120, errors="replace")
    for cmd in (["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "doc.tex"], ["bibtex", "doc"],
                ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "doc.tex"],
                ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "doc.tex"]):
        result = subprocess.run(cmd, **run)
        assert result.returncode == 0, f"{cmd[0]} failed:\n{result.stdout[-3000:]}"
    log = (tmp_path / "doc.log").read_text(errors="replace")
    blg = (tmp_path / "doc.blg").read_text(errors="replace")
    assert "Warning--" not in blg and "error message" not in blg, blg
    assert "Citation" not in log or "undefined" not in log, log[-2000:]
    assert (tmp_path / "doc.pdf").read_bytes().startswith(b"%PDF")
    return log
