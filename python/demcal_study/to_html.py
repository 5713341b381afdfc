"""The report's Markdown as one self-contained HTML file: Debian's python3-markdown (tables) converts it, and
each figure is inlined as a base64 data URI, so the file can be mailed or archived alone."""
import base64
import os
import re

import markdown

IMAGE = re.compile(r"!\[([^\]]*)\]\(([^)\s]+)\)")
STYLE = ("body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em}table{border-collapse:collapse;"
         "margin:1em 0}td,th{border:1px solid #bbb;padding:.2em .5em;text-align:left}th{background:#eee}"
         "img{max-width:100%}")


def inline_images(md, base):
    """Figures (paths relative to `base`) as data URIs; a figure whose file is missing is left out."""
    def data_uri(m):
        path = os.path.join(base, m.group(2))
        if not os.path.exists(path):
            return ""
        with open(path, "rb") as f:
            data = base64.b64encode(f.read()).decode()
        return f"![{m.group(1)}](data:image/png;base64,{data})"
    return IMAGE.sub(data_uri, md)


def to_html(md, base):
    # fenced_code: the final parameter set is one ```text block, copyable as it stands.
    body = markdown.markdown(inline_images(md, base), extensions=["tables", "fenced_code"])
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>demcal report</title><style>{STYLE}</style>"
            f"</head><body>\n{body}\n</body></html>\n")
