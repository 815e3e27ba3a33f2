"""Shared fixtures of the `needlekit serve` tests: the server as a subprocess on a free loopback port, and small HTTP
helpers on http.client (one connection per request, so that many can run at once)."""
import http.client
import json
import os
import pathlib
import re
import signal
import subprocess
import time

import pytest

CLI = os.environ.get("NEEDLEKIT_CLI", "build/bin/needlekit")
SOURCE_DIR = pathlib.Path(os.environ.get("NEEDLEKIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
EXAMPLES = SOURCE_DIR / "examples"

# Examples/evaluate_table_6_1_cone.toml as the API's JSON: the same keys and unit strings.
CONE_DESIGN = {
    "needle": {"shape": "cone", "tip_diameter": "30 um", "base_diameter": "150 um", "length": "500 um",
               "material": "silicon"},
    "array": {"needles_per_row": 10, "width": "1 cm"},
    "tissue": {"model": "skin"},
    "insertion": {"angle": "0 deg", "target_depth": "50 um"},
}


class Server:
    """A running `needlekit serve`: host, port and its process."""

    def __init__(self, process, host, port):
        self.process, self.host, self.port = process, host, port
        self.url = f"http://{host}:{port}"

    def request(self, method, path, body=None, headers=None, timeout=30):
        """(status, headers, body bytes) of one request on its own connection."""
        connection = http.client.HTTPConnection(self.host, self.port, timeout=timeout)
        try:
            if isinstance(body, (dict, list)):
                body = json.dumps(body).encode()
                headers = {"Content-Type": "application/json", **(headers or {})}
            connection.request(method, path, body=body, headers=headers or {})
            response = connection.getresponse()
            return response.status, dict(response.getheaders()), response.read()
        finally:
            connection.close()

    def json(self, method, path, body=None):
        """(status, parsed JSON body)."""
        status, _, data = self.request(method, path, body)
        return status, json.loads(data)

    def alive(self):
        return self.process.poll() is None and self.request("GET", "/api/presets")[0] == 200


def start_server(*arguments):
    """`needlekit serve --port 0` with `arguments`; waits for its 'listening on' line."""
    process = subprocess.Popen([CLI, "serve", "--port", "0", *arguments], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 30
    line = ""
    while time.monotonic() < deadline:
        line = process.stdout.readline()
        match = re.search(r"listening on http://([\d.]+):(\d+)/", line)
        if match:
            return Server(process, match.group(1), int(match.group(2)))
        if process.poll() is not None:
            break
    process.kill()
    raise RuntimeError(f"needlekit serve did not start: {line!r} {process.stderr.read()}")


def stop_server(server):
    """SIGTERM, as Ctrl-C: the server stops cleanly with exit code 130."""
    server.process.send_signal(signal.SIGTERM)
    try:
        return server.process.wait(timeout=30)
    except subprocess.TimeoutExpired:
        server.process.kill()
        raise


@pytest.fixture(scope="module")
def server():
    running = start_server()
    yield running
    assert stop_server(running) == 130, running.process.stderr.read()


def cli_json(*arguments):
    """The JSON that `needlekit ARGUMENTS --json` prints."""
    done = subprocess.run([CLI, *arguments, "--json"], capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


def cli_error(*arguments):
    """The message of a `needlekit` run that fails with bad input (exit code 2), without 'needlekit: error: '."""
    done = subprocess.run([CLI, *arguments], capture_output=True, text=True)
    assert done.returncode == 2, done
    return done.stderr.strip().removeprefix("needlekit: error: ")


def after_location(message):
    """A reader's message after its 'FILE:LINE: ' location: the same for a TOML file and a JSON body."""
    return re.sub(r"^\S+?:\d+: ", "", message)


def toml_text(design):
    """A design as a TOML file (tables of strings, integers and booleans)."""
    lines = []
    for table, entries in design.items():
        lines.append(f"[{table}]")
        for key, value in entries.items():
            lines.append(f"{key} = {json.dumps(value) if not isinstance(value, bool) else str(value).lower()}")
    return "\n".join(lines) + "\n"
