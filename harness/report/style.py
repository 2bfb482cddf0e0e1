"""The one stylesheet of every HTML page of a report."""

CSS = """
body { font-family: system-ui, sans-serif; margin: 2em; color: #222; max-width: 1400px; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 2em; }
table { border-collapse: collapse; margin: 0.5em 0; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: left; vertical-align: top; }
th { background: #f2f2f2; }
.pass { background: #e3f6e3; } .warn { background: #fff3cd; } .fail { background: #fbe0e0; font-weight: bold; } .na { color: #999; }
.meta { color: #555; font-size: 0.9em; }
code { background: #f4f4f4; padding: 0.1em 0.3em; }
img { max-width: 100%; }
"""
