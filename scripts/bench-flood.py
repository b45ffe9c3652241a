#!/usr/bin/env python3
"""A kiosk's memory through connection floods.

Starts a headless provider, then floods it FLOODS times with N connections
at once (half complete a WebSocket hello with the pairing token, half ask for
the page over HTTPS and stay open, kept alive), holds them HOLD seconds, and
drops them all. Prints the provider's resident size (VmRSS) before, at each
flood's peak, and 1, 10 and 60 s after, and the memory per idle connection.

Usage: scripts/bench-flood.py [--build build/release] [--connections 1000]
       [--floods 2] [--hold 5] [--settle 60] [--out FILE.md]
"""
import argparse
import asyncio
import base64
import json
import os
import re
import ssl
import subprocess
import sys
import tempfile
import time


def rss_kib(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return -1


def ws_frame(text):
    """One masked text frame, as a client sends it."""
    payload = text.encode()
    mask = os.urandom(4)
    head = bytes([0x81])
    n = len(payload)
    if n < 126:
        head += bytes([0x80 | n])
    else:
        head += bytes([0x80 | 126]) + n.to_bytes(2, "big")
    return head + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload))


async def open_connection(port, token, websocket, ctx, held):
    try:
        reader, writer = await asyncio.open_connection("127.0.0.1", port, ssl=ctx)
    except OSError:
        return False
    try:
        if websocket:
            key = base64.b64encode(os.urandom(16)).decode()
            writer.write((f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n"
                          f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n").encode())
            await writer.drain()
            await reader.readuntil(b"\r\n\r\n")
            hello = json.dumps({"type": "hello", "v": 1, "token": token, "client": "flood"})
            writer.write(ws_frame(hello))
            await writer.drain()
            await reader.read(2)  # the welcome's first bytes
        else:
            writer.write(f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
            await writer.drain()
            head = await reader.readuntil(b"\r\n\r\n")
            length = int(re.search(rb"Content-Length: (\d+)", head, re.I).group(1))
            await reader.readexactly(length)
    except (OSError, asyncio.IncompleteReadError, asyncio.LimitOverrunError, ssl.SSLError, AttributeError):
        writer.transport.abort()
        return False
    held.append(writer)
    return True


async def flood(port, token, n, hold, measure):
    """Opens n connections, holds them, measures, and drops them all."""
    ctx = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
    ctx.check_hostname = False
    ctx.verify_mode = ssl.CERT_NONE
    held = []
    results = await asyncio.gather(*(open_connection(port, token, i % 2 == 0, ctx, held) for i in range(n)))
    await asyncio.sleep(hold)
    peak = measure()
    for writer in held:
        writer.transport.abort()
    await asyncio.sleep(0.1)
    return sum(results), peak


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build/release")
    ap.add_argument("--connections", type=int, default=1000)
    ap.add_argument("--floods", type=int, default=2)
    ap.add_argument("--hold", type=float, default=5)
    ap.add_argument("--settle", type=float, default=60)
    ap.add_argument("--out")
    a = ap.parse_args()

    work = tempfile.mkdtemp()
    log = open(os.path.join(work, "provider.log"), "w+")
    provider = subprocess.Popen([os.path.join(a.build, "bin", "umf-provider"), "--headless", "--port", "0", "--no-qr",
                                 "--config-dir", os.path.join(work, "cfg")], stdout=log, stderr=subprocess.STDOUT)
    try:
        url = None
        for _ in range(100):
            log.seek(0)
            m = re.search(r"pairing URL: https://127\.0\.0\.1:(\d+)/#t=([^&\s]+)&fp=", log.read())
            if m:
                url = m
                break
            time.sleep(0.1)
        if not url:
            log.seek(0)
            sys.exit("no provider:\n" + log.read())
        port, token = int(url.group(1)), url.group(2)
        time.sleep(1)
        rows = [("start", rss_kib(provider.pid), "")]
        per_connection = []
        for k in range(1, a.floods + 1):
            before = rss_kib(provider.pid)
            t0 = time.monotonic()
            opened, peak = asyncio.run(flood(port, token, a.connections, a.hold, lambda: rss_kib(provider.pid)))
            rows.append((f"flood {k}: {opened} of {a.connections} open", peak, ""))
            per_connection.append((peak - before) / max(opened, 1))
            t0 = time.monotonic()
            for after in (1, 10, a.settle):
                time.sleep(max(0.0, t0 + after - time.monotonic()))
                rows.append((f"flood {k} + {after:g} s", rss_kib(provider.pid), ""))
        start = rows[0][1]
        lines = ["| moment | VmRSS | vs start |", "|---|---|---|"]
        for name, kib, _ in rows:
            lines.append(f"| {name} | {kib / 1024:.1f} MiB | {100.0 * (kib - start) / start:+.0f} % |")
        lines.append("")
        lines.append("Memory per open connection (peak minus the size before the flood, over the connections "
                     "opened): " + ", ".join(f"{c:.0f} KiB" for c in per_connection))
        text = "\n".join(lines)
        print(text)
        if a.out:
            with open(a.out, "w") as f:
                f.write(text + "\n")
        final = rows[-1][1]
        return 0 if final <= start * 1.2 else 1
    finally:
        provider.terminate()
        provider.wait(10)


if __name__ == "__main__":
    sys.exit(main())
