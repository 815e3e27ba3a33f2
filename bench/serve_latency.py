"""Latency of `needlekit serve`'s POST /api/evaluate on localhost (issue 37 item 3: p99 < 5 ms over 10^4 requests).

Starts `needlekit serve --port 0`, sends the Table 6.1 cone (examples/evaluate_table_6_1_cone.toml as JSON) 10^4
times, one request at a time on one keep-alive connection (as the page's debounced calls come), after 200 warm-up
requests, and prints p50, p90, p99 and the maximum of the round trip measured by the client (Python's http.client,
so the figures include the client's own time), the server's CPU time per request and the machine's load average (on a
shared machine the tail is time spent waiting for a core). Exit code 1 when p99 >= 5 ms.

    /usr/bin/python3 bench/serve_latency.py [build/bin/needlekit] [--requests N]
"""
import argparse
import os
import http.client
import json
import pathlib
import re
import signal
import statistics
import subprocess
import sys
import time
import tomllib

ROOT = pathlib.Path(__file__).resolve().parents[1]


def server_cpu_seconds(pid):
    """User + system CPU time of the server process so far (/proc/PID/stat, clock ticks)."""
    fields = pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cli", nargs="?", default=str(ROOT / "build" / "bin" / "needlekit"))
    parser.add_argument("--requests", type=int, default=10_000)
    arguments = parser.parse_args()
    with open(ROOT / "examples" / "evaluate_table_6_1_cone.toml", "rb") as file:
        body = json.dumps(tomllib.load(file)).encode()
    server = subprocess.Popen([arguments.cli, "serve", "--port", "0"], stdout=subprocess.PIPE, text=True)
    try:
        match = re.search(r"http://([\d.]+):(\d+)/", server.stdout.readline())
        connection = http.client.HTTPConnection(match.group(1), int(match.group(2)))
        headers = {"Content-Type": "application/json"}

        def one():
            start = time.perf_counter_ns()
            connection.request("POST", "/api/evaluate", body=body, headers=headers)
            response = connection.getresponse()
            data = response.read()
            elapsed = time.perf_counter_ns() - start
            if response.status != 200:
                raise RuntimeError(f"{response.status}: {data[:200]!r}")
            return elapsed

        for _ in range(200):
            one()
        cpu_before = server_cpu_seconds(server.pid)
        times = sorted(one() for _ in range(arguments.requests))
        cpu = server_cpu_seconds(server.pid) - cpu_before
    finally:
        server.send_signal(signal.SIGINT)
        server.wait(timeout=30)

    def quantile(q):
        return times[min(len(times) - 1, int(q * len(times)))] / 1e6

    p50, p90, p99 = quantile(0.50), quantile(0.90), quantile(0.99)
    print(f"POST /api/evaluate, {len(times)} requests on one keep-alive connection: p50 {p50:.3f} ms, p90 {p90:.3f} "
          f"ms, p99 {p99:.3f} ms, max {times[-1] / 1e6:.3f} ms, mean {statistics.fmean(times) / 1e6:.3f} ms; server CPU "
          f"{cpu / len(times) * 1e3:.3f} ms per request; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} "
          f"cores")
    return 0 if p99 < 5 else 1


if __name__ == "__main__":
    sys.exit(main())
