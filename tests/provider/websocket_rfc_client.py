#!/usr/bin/python3
"""An independent WebSocket client that checks the provider against RFC 6455.

Run by tests/provider/websocket_rfc_test.cpp against an in-process server:

    /usr/bin/python3 websocket_rfc_client.py --port P --token T --case NAME

NAME is one case, a comma-separated list, or "all". Each case opens its own
connection(s) and prints one JSON line with what it observed; it judges
nothing, the C++ test does:

    {"case": NAME,
     "events": [...],        # in arrival order, see below
     "close_code": int|null, # the code in the provider's close frame
     "tcp_closed": bool,     # the provider ended TLS and TCP after closing
     "alive_after": bool,    # a fresh connection was welcomed afterwards
     "error": str|null,      # a client-side failure (timeout, refused, ...)
     "extra": {...}}         # case-specific observations

An event is {"kind": "text", "type", "id", "code"} for a JSON message,
{"kind": "binary", "len"}, {"kind": "ping"|"pong", "payload": hex},
{"kind": "close", "code", "reason"}, {"kind": "eof"} or {"kind": "timeout"}.

Cases that a conforming client library cannot produce (invalid UTF-8, bad
opcodes, unmasked frames, reserved bits, malformed control frames, exact
fragment boundaries) use a raw client: TLS from the standard library, the
HTTP upgrade by hand and frames built here. The others use Debian's
python3-websockets (the legacy asyncio API of websockets 10). The
certificate is not verified: these cases are about framing, not pinning.
"""

import argparse
import asyncio
import base64
import hashlib
import json
import os
import socket
import ssl
import struct
import sys
import time

CASE_TIMEOUT = 4.0  # seconds for everything a case waits for
GUID = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11"

OP_CONT, OP_TEXT, OP_BINARY, OP_CLOSE, OP_PING, OP_PONG = 0x0, 0x1, 0x2, 0x8, 0x9, 0xA

ARGS = None


def tls_context():
    ctx = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
    ctx.check_hostname = False
    ctx.verify_mode = ssl.CERT_NONE
    return ctx


def hello(msg_id=1):
    return json.dumps({"type": "hello", "v": 1, "id": msg_id, "token": ARGS.token,
                      "client": "websocket_rfc_client.py"})


def aim(msg_id, **extra):
    m = {"type": "aim", "v": 1, "id": msg_id, "point": [10.5, 4.25], "confidence": 0.9}
    m.update(extra)
    return json.dumps(m, ensure_ascii=False)


def text_event(data):
    try:
        m = json.loads(data)
    except Exception:  # noqa: BLE001 - reported, not raised
        return {"kind": "text", "type": None, "raw": data[:200]}
    if not isinstance(m, dict):
        return {"kind": "text", "type": None, "raw": data[:200]}
    return {"kind": "text", "type": m.get("type"), "id": m.get("id"), "code": m.get("code")}


def close_event(payload):
    if len(payload) >= 2:
        code = struct.unpack("!H", payload[:2])[0]
        return {"kind": "close", "code": code, "reason": payload[2:].decode("utf-8", "replace")}
    return {"kind": "close", "code": None, "reason": ""}


def frame(opcode, payload=b"", fin=True, rsv=0, mask=True):
    """One frame, masked as a client's must be unless told otherwise."""
    if isinstance(payload, str):
        payload = payload.encode("utf-8")
    b0 = (0x80 if fin else 0) | (rsv << 4) | opcode
    mbit = 0x80 if mask else 0
    n = len(payload)
    if n < 126:
        head = bytes([b0, mbit | n])
    elif n < 65536:
        head = bytes([b0, mbit | 126]) + struct.pack("!H", n)
    else:
        head = bytes([b0, mbit | 127]) + struct.pack("!Q", n)
    if mask:
        key = os.urandom(4)
        n4 = (n + 3) // 4
        k = int.from_bytes(key * n4, "big") if n else 0
        p = int.from_bytes(payload + b"\0" * (4 * n4 - n), "big") if n else 0
        payload = (p ^ k).to_bytes(4 * n4, "big")[:n] if n else b""
        head += key
    return head + payload


def close_payload(code, reason=b""):
    return struct.pack("!H", code) + reason


class Raw:
    """A WebSocket client over ssl + socket, the upgrade done by hand."""

    def __init__(self, deadline):
        self.deadline = deadline
        self.events = []
        self.buf = b""
        self.close_code = None
        self.tcp_closed = False
        self.msg_op = None
        self.msg = b""
        plain = socket.create_connection(("127.0.0.1", ARGS.port), timeout=self.remaining())
        self.sock = tls_context().wrap_socket(plain, server_hostname="127.0.0.1")
        key = base64.b64encode(os.urandom(16)).decode()
        request = (f"GET /ws HTTP/1.1\r\nHost: 127.0.0.1:{ARGS.port}\r\nUpgrade: websocket\r\n"
                   f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n")
        self.sock.sendall(request.encode())
        while b"\r\n\r\n" not in self.buf:
            chunk = self.recv_some()
            if not chunk:
                raise RuntimeError("connection ended during the upgrade")
            self.buf += chunk
        head, self.buf = self.buf.split(b"\r\n\r\n", 1)
        lines = head.decode("latin-1").split("\r\n")
        if lines[0].split(" ")[1] != "101":
            raise RuntimeError("upgrade refused: " + lines[0])
        headers = {k.strip().lower(): v.strip() for k, _, v in (line.partition(":") for line in lines[1:])}
        accept = base64.b64encode(hashlib.sha1((key + GUID).encode()).digest()).decode()
        if headers.get("sec-websocket-accept") != accept:
            raise RuntimeError("bad Sec-WebSocket-Accept")
        if headers.get("sec-websocket-extensions"):
            raise RuntimeError("an extension was negotiated unasked")

    def remaining(self):
        return max(0.01, self.deadline - time.monotonic())

    def recv_some(self):
        self.sock.settimeout(self.remaining())
        return self.sock.recv(65536)

    def send(self, data):
        self.sock.settimeout(self.remaining())
        self.sock.sendall(data)

    def send_frame(self, *a, **kw):
        self.send(frame(*a, **kw))

    def _need(self, n):
        while len(self.buf) < n:
            chunk = self.recv_some()
            if not chunk:
                raise EOFError
            self.buf += chunk

    def _frame(self):
        self._need(2)
        b0, b1 = self.buf[0], self.buf[1]
        n, off = b1 & 0x7F, 2
        if n == 126:
            self._need(4)
            n, off = struct.unpack("!H", self.buf[2:4])[0], 4
        elif n == 127:
            self._need(10)
            n, off = struct.unpack("!Q", self.buf[2:10])[0], 10
        if b1 & 0x80:
            raise RuntimeError("the server masked a frame")
        if b0 & 0x70:
            raise RuntimeError("the server set reserved bits")
        self._need(off + n)
        payload, self.buf = self.buf[off:off + n], self.buf[off + n:]
        return bool(b0 & 0x80), b0 & 0x0F, payload

    def next_event(self):
        """The next message or control frame; eof or timeout end the stream."""
        while True:
            try:
                fin, op, payload = self._frame()
            except EOFError:
                ev = {"kind": "eof"}
            except (socket.timeout, TimeoutError):
                ev = {"kind": "timeout"}
            except (ssl.SSLError, OSError) as e:
                ev = {"kind": "eof", "error": type(e).__name__}
            else:
                if op in (OP_TEXT, OP_BINARY, OP_CONT):
                    if op != OP_CONT:
                        self.msg_op, self.msg = op, b""
                    self.msg += payload
                    if not fin:
                        continue
                    if self.msg_op == OP_TEXT:
                        ev = text_event(self.msg.decode("utf-8", "replace"))
                    else:
                        ev = {"kind": "binary", "len": len(self.msg)}
                elif op == OP_CLOSE:
                    ev = close_event(payload)
                    self.close_code = ev["code"]
                elif op in (OP_PING, OP_PONG):
                    ev = {"kind": "ping" if op == OP_PING else "pong", "payload": payload.hex()}
                else:
                    ev = {"kind": "opcode", "opcode": op}
            self.events.append(ev)
            return ev

    def read_until(self, pred):
        """Events until pred(event), a close, eof or timeout; the last one."""
        while True:
            ev = self.next_event()
            if pred(ev) or ev["kind"] in ("close", "eof", "timeout"):
                return ev

    def read_texts(self, n):
        got = []
        while len(got) < n:
            ev = self.read_until(lambda e: e["kind"] == "text")
            if ev["kind"] != "text":
                break
            got.append(ev)
        return got

    def welcome(self):
        self.send_frame(OP_TEXT, hello())
        ev = self.read_until(lambda e: e["kind"] == "text")
        if ev.get("type") != "welcome":
            raise RuntimeError(f"no welcome: {ev}")

    def expect_close(self):
        """Waits for the provider's close frame, then for it to end TLS and
        TCP: after its close_notify this side answers with its own, and the
        provider must then close the TCP connection."""
        ev = self.events[-1] if self.events else None
        if not ev or ev["kind"] not in ("close", "eof", "timeout"):
            self.read_until(lambda e: False)
        if self.events[-1]["kind"] == "close":
            end = self.read_until(lambda e: False)  # the TLS close_notify: eof
            if end["kind"] != "eof":
                return
        if self.events[-1]["kind"] == "timeout":
            return
        try:
            self.sock.settimeout(self.remaining())
            plain = self.sock.unwrap()
        except (ssl.SSLError, OSError):
            self.tcp_closed = True  # already gone
            return
        try:
            while True:
                plain.settimeout(self.remaining())
                if not plain.recv(4096):
                    self.tcp_closed = True
                    return
        except ConnectionResetError:
            self.tcp_closed = True
        except (socket.timeout, TimeoutError, OSError):
            pass

    def close(self):
        try:
            self.sock.close()
        except OSError:
            pass


def raw_case(body):
    """Runs body(raw) on a fresh raw connection; its observations."""
    out = {"events": [], "close_code": None, "tcp_closed": False, "error": None, "extra": {}}
    raw = None
    try:
        raw = Raw(time.monotonic() + CASE_TIMEOUT)
        extra = body(raw)
        if extra:
            out["extra"].update(extra)
    except Exception as e:  # noqa: BLE001 - reported to the C++ test
        out["error"] = f"{type(e).__name__}: {e}"
    finally:
        if raw:
            out["events"] = raw.events
            out["close_code"] = raw.close_code
            out["tcp_closed"] = raw.tcp_closed
            raw.close()
    return out


def lib_case(coro_fn):
    """Runs coro_fn(ws, out) on a websockets connection; its observations."""
    import websockets  # noqa: WPS433 - only the library cases need it

    out = {"events": [], "close_code": None, "tcp_closed": False, "error": None, "extra": {}}

    async def run():
        async with websockets.connect(f"wss://127.0.0.1:{ARGS.port}/ws", ssl=tls_context(),
                                      open_timeout=CASE_TIMEOUT, close_timeout=2, ping_interval=None,
                                      max_size=None, compression=None) as ws:
            try:
                await coro_fn(ws, out)
            finally:
                if ws.closed or out["extra"].get("wait_closed"):
                    try:
                        await asyncio.wait_for(ws.wait_closed(), 2.5)
                        out["tcp_closed"] = True
                    except asyncio.TimeoutError:
                        pass
                    if ws.close_code is not None and ws.close_code != 1006:
                        out["close_code"] = ws.close_code
                        out["events"].append({"kind": "close", "code": ws.close_code, "reason": ws.close_reason})
                out["extra"].pop("wait_closed", None)

    try:
        asyncio.run(asyncio.wait_for(run(), CASE_TIMEOUT + 1))
    except Exception as e:  # noqa: BLE001 - reported to the C++ test
        out["error"] = f"{type(e).__name__}: {e}"
    return out


async def lib_recv(ws, out):
    import websockets

    try:
        msg = await asyncio.wait_for(ws.recv(), CASE_TIMEOUT)
    except asyncio.TimeoutError:
        out["events"].append({"kind": "timeout"})
        return None
    except websockets.ConnectionClosed:
        out["events"].append({"kind": "eof"})
        return None
    ev = text_event(msg) if isinstance(msg, str) else {"kind": "binary", "len": len(msg)}
    out["events"].append(ev)
    return ev


async def lib_welcome(ws, out):
    await ws.send(hello())
    ev = await lib_recv(ws, out)
    if not ev or ev.get("type") != "welcome":
        raise RuntimeError(f"no welcome: {ev}")


async def lib_ping(ws, out, payload):
    waiter = await ws.ping(payload)
    try:
        await asyncio.wait_for(waiter, CASE_TIMEOUT / 2)
        # The library resolves the waiter only for a pong carrying this
        # payload (the only ping outstanding).
        out["events"].append({"kind": "pong", "payload": payload.hex()})
    except asyncio.TimeoutError:
        out["events"].append({"kind": "timeout", "waiting_for": "pong " + payload.hex()})


# ---- the cases ----------------------------------------------------------------


def c_fragmented_raw(raw):
    # hello in three frames: text (FIN=0), continuation (FIN=0), continuation (FIN=1).
    h = hello().encode()
    a, b = len(h) // 3, 2 * len(h) // 3
    raw.send_frame(OP_TEXT, h[:a], fin=False)
    raw.send_frame(OP_CONT, h[a:b], fin=False)
    raw.send_frame(OP_CONT, h[b:], fin=True)
    raw.read_until(lambda e: e["kind"] == "text")
    # An aim in three fragments with a ping between the first two.
    m = aim(2).encode()
    raw.send_frame(OP_TEXT, m[:10], fin=False)
    raw.send_frame(OP_PING, b"mid-message \x00\xff", fin=True)
    raw.send_frame(OP_CONT, m[10:20], fin=False)
    raw.send_frame(OP_CONT, m[20:], fin=True)
    raw.read_until(lambda e: e["kind"] == "text")
    # The pong comes before the target (the message is not complete until
    # the last fragment); read on briefly in case the order is otherwise.
    if not any(e["kind"] == "pong" for e in raw.events):
        raw.read_until(lambda e: e["kind"] == "pong")


def c_utf8_split_across_fragments(raw):
    raw.welcome()
    # "é" (c3 a9) and "😀" (f0 9f 98 80) split across frame boundaries: valid.
    m = aim(3, note="caf\u00e9 \U0001F600").encode()
    i = m.index(b"\xc3") + 1
    j = m.index(b"\xf0") + 2
    raw.send_frame(OP_TEXT, m[:i], fin=False)
    raw.send_frame(OP_CONT, m[i:j], fin=False)
    raw.send_frame(OP_CONT, m[j:], fin=True)
    raw.read_until(lambda e: e["kind"] == "text")


async def c_fragmented_lib(ws, out):
    # The library's fragmented send: a text frame, continuations, and an
    # empty final continuation.
    await ws.send(iter(['{"type":"hello","v":1,"id":1,', f'"token":"{ARGS.token}",', '"client":"lib"}']))
    ev = await lib_recv(ws, out)
    if not ev or ev.get("type") != "welcome":
        return
    ping_payload = b"between fragments"
    waiters = []

    async def fragments():
        m = aim(2)
        yield m[:12]
        waiters.append(await ws.ping(ping_payload))
        yield m[12:30]
        yield m[30:]

    await ws.send(fragments())
    await lib_recv(ws, out)
    try:
        await asyncio.wait_for(waiters[0], CASE_TIMEOUT / 2)
        out["events"].append({"kind": "pong", "payload": ping_payload.hex()})
    except asyncio.TimeoutError:
        out["events"].append({"kind": "timeout", "waiting_for": "pong"})


async def c_ping_pong(ws, out):
    await lib_welcome(ws, out)
    await lib_ping(ws, out, b"umf \x00\x01\xfe\xff ping")
    await lib_ping(ws, out, bytes(range(125)))  # the largest control payload
    await ws.pong(b"unsolicited")  # must be ignored
    await ws.send(aim(4))
    await lib_recv(ws, out)


def c_ping_pong_raw(raw):
    raw.welcome()
    raw.send_frame(OP_PING, b"")
    raw.read_until(lambda e: e["kind"] == "pong")
    raw.send_frame(OP_PING, b"raw \x80\x81 payload")
    raw.read_until(lambda e: e["kind"] == "pong")
    raw.send_frame(OP_PONG, b"unsolicited")
    raw.send_frame(OP_TEXT, aim(5))
    raw.read_until(lambda e: e["kind"] == "text")


def c_close_normal(raw):
    raw.welcome()
    raw.send_frame(OP_CLOSE, close_payload(1000, b"bye"))
    raw.expect_close()


async def c_close_normal_lib(ws, out):
    await lib_welcome(ws, out)
    await asyncio.wait_for(ws.close(1000, "bye"), CASE_TIMEOUT)
    out["extra"]["wait_closed"] = True


def close_then_expect(payload):
    def body(raw):
        raw.welcome()
        raw.send_frame(OP_CLOSE, payload)
        raw.expect_close()
    return body


def violation_after_welcome(*frames):
    def body(raw):
        raw.welcome()
        raw.send(b"".join(frames))
        raw.expect_close()
    return body


def c_invalid_utf8(raw):
    raw.welcome()
    raw.send_frame(OP_TEXT, b'{"type":"seeking","v":1,"x":"\xc3\x28"}')
    raw.expect_close()


def c_invalid_utf8_fragment(raw):
    # The bad byte is in the first fragment; the message never completes.
    raw.welcome()
    raw.send_frame(OP_TEXT, b'{"type":"seeking","v":1,"x":"\xff', fin=False)
    raw.expect_close()


def c_invalid_utf8_truncated(raw):
    # Each fragment is fine so far but the message ends inside a sequence.
    raw.welcome()
    raw.send_frame(OP_TEXT, b'{"type":"seeking","v":1}', fin=False)
    raw.send_frame(OP_CONT, b" \xe2\x82", fin=True)
    raw.expect_close()


def c_max_size_accepted(raw):
    # Exactly max_message_bytes (16384) is read; one more is not (below).
    raw.welcome()
    base = aim(6, pad="")
    m = aim(6, pad="x" * (16384 - len(base)))
    assert len(m.encode()) == 16384
    raw.send_frame(OP_TEXT, m)
    raw.read_until(lambda e: e["kind"] == "text")
    return {"sent_bytes": len(m)}


def c_oversize_by_one(raw):
    raw.welcome()
    base = aim(6, pad="")
    m = aim(6, pad="x" * (16385 - len(base)))
    raw.send_frame(OP_TEXT, m)
    raw.expect_close()
    return {"sent_bytes": len(m)}


async def c_oversize_single(ws, out):
    await lib_welcome(ws, out)
    import websockets

    try:
        await ws.send(aim(7, pad="x" * 20000))
    except websockets.ConnectionClosed:
        pass
    await lib_recv(ws, out)
    out["extra"]["wait_closed"] = True


def c_oversize_fragmented(raw):
    raw.welcome()
    m = aim(8, pad="x" * 20000).encode()
    chunks = [m[i:i + 1000] for i in range(0, len(m), 1000)]
    sent = 0
    try:
        for k, c in enumerate(chunks):
            raw.send_frame(OP_TEXT if k == 0 else OP_CONT, c, fin=(k == len(chunks) - 1))
            sent += 1
    except OSError:
        pass  # the provider may have closed before the last fragments
    raw.expect_close()
    return {"fragments": len(chunks), "fragments_sent": sent}


async def c_oversize_fragmented_lib(ws, out):
    await lib_welcome(ws, out)
    import websockets

    m = aim(9, pad="x" * 20000)
    try:
        await ws.send(iter([m[i:i + 1000] for i in range(0, len(m), 1000)]))
    except websockets.ConnectionClosed:
        pass
    await lib_recv(ws, out)
    out["extra"]["wait_closed"] = True


async def c_binary_lib(ws, out):
    await lib_welcome(ws, out)
    await ws.send(b"\x00\xffbinary\x13")
    await lib_recv(ws, out)
    await ws.send(aim(10))
    await lib_recv(ws, out)


def c_binary_fragmented(raw):
    raw.welcome()
    raw.send_frame(OP_BINARY, b"\x00\x01", fin=False)
    raw.send_frame(OP_CONT, b"\xff", fin=True)
    raw.read_until(lambda e: e["kind"] == "text")
    raw.send_frame(OP_TEXT, aim(11))
    raw.read_until(lambda e: e["kind"] == "text")


def c_burst(raw):
    # 50 requests in one TLS write: aims 1..10 (the aim limit's burst), then
    # 40 messages of an unknown type, each answered by a bad_request that
    # carries its id. 50 replies, in order.
    raw.welcome()
    msgs = [aim(i) for i in range(1, 11)] + [json.dumps({"type": "teleport", "v": 1, "id": i}) for i in range(11, 51)]
    raw.send(b"".join(frame(OP_TEXT, m) for m in msgs))
    raw.read_texts(50)


async def c_burst_lib(ws, out):
    await lib_welcome(ws, out)
    for i in range(1, 11):
        await ws.send(aim(i))
    for _ in range(10):
        if not await lib_recv(ws, out):
            break


def c_survives(raw):
    raw.welcome()
    raw.send_frame(OP_CLOSE, close_payload(1000))
    raw.expect_close()


CASES = {
    # 1. fragmentation
    "fragmented_raw": lambda: raw_case(c_fragmented_raw),
    "fragmented_lib": lambda: lib_case(c_fragmented_lib),
    "utf8_split_across_fragments": lambda: raw_case(c_utf8_split_across_fragments),
    # 2. ping and pong
    "ping_pong_lib": lambda: lib_case(c_ping_pong),
    "ping_pong_raw": lambda: raw_case(c_ping_pong_raw),
    # 3. the closing handshake
    "close_normal": lambda: raw_case(c_close_normal),
    "close_normal_lib": lambda: lib_case(c_close_normal_lib),
    "close_empty": lambda: raw_case(close_then_expect(b"")),
    "close_code_1005": lambda: raw_case(close_then_expect(close_payload(1005))),
    "close_code_999": lambda: raw_case(close_then_expect(close_payload(999))),
    "close_code_2000": lambda: raw_case(close_then_expect(close_payload(2000))),
    "close_one_byte": lambda: raw_case(close_then_expect(b"\x03")),
    "close_reason_bad_utf8": lambda: raw_case(close_then_expect(close_payload(1000, b"bad \xff\xfe"))),
    # 4. invalid UTF-8 in text
    "invalid_utf8": lambda: raw_case(c_invalid_utf8),
    "invalid_utf8_fragment": lambda: raw_case(c_invalid_utf8_fragment),
    "invalid_utf8_truncated": lambda: raw_case(c_invalid_utf8_truncated),
    # 5. size
    "max_size_accepted": lambda: raw_case(c_max_size_accepted),
    "oversize_by_one": lambda: raw_case(c_oversize_by_one),
    "oversize_single_lib": lambda: lib_case(c_oversize_single),
    "oversize_fragmented": lambda: raw_case(c_oversize_fragmented),
    "oversize_fragmented_lib": lambda: lib_case(c_oversize_fragmented_lib),
    # 6. protocol errors
    "unmasked": lambda: raw_case(violation_after_welcome(frame(OP_TEXT, aim(12), mask=False))),
    "rsv1": lambda: raw_case(violation_after_welcome(frame(OP_TEXT, aim(12), rsv=4))),
    "rsv2_ping": lambda: raw_case(violation_after_welcome(frame(OP_PING, b"x", rsv=2))),
    "opcode_3": lambda: raw_case(violation_after_welcome(frame(0x3, b"data"))),
    "opcode_b": lambda: raw_case(violation_after_welcome(frame(0xB, b""))),
    "control_too_long": lambda: raw_case(violation_after_welcome(frame(OP_PING, b"p" * 126))),
    "fragmented_ping": lambda: raw_case(violation_after_welcome(frame(OP_PING, b"half", fin=False),
                                                                frame(OP_CONT, b"rest"))),
    "orphan_continuation": lambda: raw_case(violation_after_welcome(frame(OP_CONT, aim(12)))),
    "text_inside_fragmented": lambda: raw_case(violation_after_welcome(frame(OP_TEXT, aim(12)[:5], fin=False),
                                                                       frame(OP_TEXT, aim(13)))),
    # 7. binary
    "binary_lib": lambda: lib_case(c_binary_lib),
    "binary_fragmented": lambda: raw_case(c_binary_fragmented),
    # 8. pipelining
    "burst": lambda: raw_case(c_burst),
    "burst_lib": lambda: lib_case(c_burst_lib),
    # 9. a fresh connection
    "survives": lambda: raw_case(c_survives),
}


def alive():
    """Whether a fresh connection is still welcomed."""
    r = raw_case(lambda raw: raw.welcome())
    return r["error"] is None


def main():
    global ARGS
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--port", type=int, required=True)
    parser.add_argument("--token", required=True)
    parser.add_argument("--case", required=True, help="a name, names separated by commas, or all")
    parser.add_argument("--list", action="store_true")
    ARGS = parser.parse_args()
    names = list(CASES) if ARGS.case == "all" else ARGS.case.split(",")
    unknown = [n for n in names if n not in CASES]
    if unknown:
        print(json.dumps({"error": "unknown case(s): " + ", ".join(unknown)}), flush=True)
        return 2
    for name in names:
        start = time.monotonic()
        result = {"case": name}
        result.update(CASES[name]())
        result["alive_after"] = alive()
        result["seconds"] = round(time.monotonic() - start, 3)
        print(json.dumps(result), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
