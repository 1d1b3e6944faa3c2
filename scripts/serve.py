#!/usr/bin/env python3
"""Serves a folder on a local address for the demo: `python3 scripts/serve.py DIR HOST PORT`.

Python's http.server with two changes: `.wasm` is always `application/wasm` (which streaming
compilation needs, whatever the system's MIME table says) and nothing is cached, so a rebuilt
package shows up on reload.
"""

import functools
import http.server
import sys


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".wasm": "application/wasm",
        ".js": "text/javascript",
        ".mjs": "text/javascript",
        ".css": "text/css",
        ".json": "application/json",
        ".pgm": "image/x-portable-graymap",
        ".yaml": "application/yaml",
    }

    def end_headers(self):
        self.send_header("Cache-Control", "no-store")
        super().end_headers()


def main():
    root, host, port = sys.argv[1], sys.argv[2], int(sys.argv[3])
    handler = functools.partial(Handler, directory=root)
    with http.server.ThreadingHTTPServer((host, port), handler) as httpd:
        print(f"serving {root}/ on http://{host}:{port}/  (Ctrl+C to stop)", flush=True)
        try:
            httpd.serve_forever()
        except KeyboardInterrupt:
            pass


if __name__ == "__main__":
    main()
