"""The 3-D view of a World, Scene or Animation in a notebook (``_repr_html_``): the .glb
``ontogen run`` writes, drawn by the studio's page code (three.js, bundled at build time
into ``viewer.js`` beside this file) in a page of its own, inlined whole: nothing is
fetched when it shows, so it works offline and in a saved notebook."""

import base64
import html
import json
import os

_VIEWER = os.path.join(os.path.dirname(__file__), "viewer.js")
_script = None


def viewer_script():
    """The bundled viewer (three.js and the studio's 3-D view), or None when the module was
    built without it (no esbuild and three.js at build time)."""
    global _script
    if _script is None and os.path.exists(_VIEWER):
        with open(_VIEWER, encoding="utf-8") as f:
            text = f.read()
        # Inlined in a <script> element, the text must not close it.
        if "</script" in text.lower():
            raise RuntimeError(f"{_VIEWER} holds '</script' and cannot be inlined")
        _script = text
    return _script


_STYLE = """
html, body { margin: 0; height: 100%; background: #2a2d33; color: #d8dade;
  font: 13px system-ui, sans-serif; overflow: hidden; }
body { display: flex; flex-direction: column; }
canvas { flex: 1; min-height: 0; width: 100%; display: block; }
.row { display: flex; gap: 8px; align-items: center; padding: 6px 8px; }
.row[hidden] { display: none; }
input[type=range] { flex: 1; }
output { min-width: 6em; text-align: right; font-variant-numeric: tabular-nums; }
"""


def page(glb, times=(), title="ontogen"):
    """A whole HTML page showing ``glb`` (bytes): the model turned with the mouse and, for
    more than one frame time, a time slider and a Play button over ``times`` (seconds)."""
    script = viewer_script()
    if script is None:
        raise RuntimeError("ontogen was built without its 3-D viewer (viewer.js): esbuild and three.js were "
                           "missing at build time (docs/PYTHON.md)")
    times = [float(t) for t in times]
    model = base64.b64encode(bytes(glb)).decode("ascii")
    return (
        "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<title>{html.escape(title)}</title>\n<style>{_STYLE}</style>\n</head>\n<body>\n"
        "<canvas id=\"canvas\"></canvas>\n"
        "<div class=\"row\" id=\"time-row\" hidden>\n"
        "  <button id=\"play\" type=\"button\">Play</button>\n"
        "  <input id=\"time\" type=\"range\" min=\"0\" max=\"1\" step=\"any\" value=\"1\">\n"
        "  <output id=\"time-value\"></output>\n</div>\n"
        f"<script type=\"application/json\" id=\"ontogen-times\">{json.dumps(times)}</script>\n"
        f"<script type=\"application/octet-stream\" id=\"ontogen-model\">{model}</script>\n"
        f"<script>{script}</script>\n</body>\n</html>\n"
    )


def frame(glb, times=(), height=480):
    """The page of ``glb`` in an iframe (its srcdoc), as a notebook's output shows it: each
    view keeps its own page, script and ids however many a notebook shows."""
    document = page(glb, times)
    return (f"<iframe srcdoc=\"{html.escape(document, quote=True)}\" "
            f"style=\"width: 100%; height: {int(height)}px; border: 0\" "
            "title=\"ontogen 3-D view\"></iframe>")


def repr_html(glb, times=()):
    """``_repr_html_``'s answer: the iframe, or None (the text repr) without the viewer."""
    if viewer_script() is None:
        return None
    return frame(glb, times)
