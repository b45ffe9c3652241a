#!/usr/bin/env python3
"""A TCP relay that cuts one connection once: what a phone's Wi-Fi does when
the screen turns off or its owner walks away. It listens on 127.0.0.1 (the
port it prints first, on a line of its own), relays every connection to
TARGET_PORT, and when CUT_AT bytes have gone from the target to clients in
all (DIRECTION down, the default; up: from clients to the target), closes
the connection that carried them, client and target side, with a reset. It counts the bytes carried each way and writes them to COUNT_FILE
("DOWN UP\\n") as they pass (every MiB at most), so a test reads how much a
transfer cost once its client has the bytes. Given CHANGE_FILE and
CHANGE_AT, it also changes that byte of that file at the moment of the cut
(the size kept), as a user who edits a file while it is being sent; with
"keep" after them, it changes the byte then and leaves the connection be.

usage: cutting_relay.py TARGET_PORT CUT_AT COUNT_FILE [down|up [CHANGE_FILE CHANGE_AT [keep]]]
"""
import os
import socket
import struct
import sys
import threading

target_port, cut_at, count_file = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
cut_direction = sys.argv[4] if len(sys.argv) > 4 else "down"
change_file, change_at = (sys.argv[5], int(sys.argv[6])) if len(sys.argv) > 6 else (None, 0)
keep_connection = len(sys.argv) > 7 and sys.argv[7] == "keep"
lock = threading.Lock()
carried = {"down": 0, "up": 0}
cut_done = False


def write_counts():
    """Whole or not at all: a test may read the file while the relay still
    counts (a truncated file read as empty once failed a test)."""
    part = f"{count_file}.{threading.get_ident()}.part"
    with open(part, "w") as f:
        f.write(f"{carried['down']} {carried['up']}\n")
    os.replace(part, count_file)


def reset(sock):
    """Ends the connection at once, as a dropped link does: no lingering
    (a reset where the kernel can), and the relay's other thread, blocked
    reading the same socket, woken by the shutdown."""
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        sock.shutdown(socket.SHUT_RDWR)
    except OSError:
        pass


def change_byte():
    with open(change_file, "r+b") as f:
        f.seek(change_at)
        byte = f.read(1)
        f.seek(change_at)
        f.write(bytes([byte[0] ^ 0x5A]))


def pump(src, dst, direction, pair):
    """Moves bytes src -> dst in the kernel (splice through a pipe), so the
    relay keeps up with a TLS transfer on loopback."""
    global cut_done
    pipe_r, pipe_w = os.pipe()
    try:
        while True:
            want = 1 << 20
            with lock:
                if direction == cut_direction and not cut_done:
                    want = max(1, min(want, cut_at - carried[direction]))
            n = os.splice(src.fileno(), pipe_w, want)
            if n == 0:
                break
            left = n
            while left > 0:
                left -= os.splice(pipe_r, dst.fileno(), left)
            cut = False
            with lock:
                carried[direction] += n
                if direction == cut_direction and not cut_done and carried[direction] >= cut_at:
                    cut_done = cut = True
                write_counts()
            if cut:
                if change_file:
                    change_byte()
                if not keep_connection:
                    for s in pair:
                        reset(s)
                    return
    except OSError:
        pass
    finally:
        os.close(pipe_r)
        os.close(pipe_w)
        try:
            dst.shutdown(socket.SHUT_WR)
        except OSError:
            pass


def relay(client):
    try:
        upstream = socket.create_connection(("127.0.0.1", target_port))
    except OSError:
        client.close()
        return
    pair = (client, upstream)
    threads = [threading.Thread(target=pump, args=(client, upstream, "up", pair), daemon=True),
               threading.Thread(target=pump, args=(upstream, client, "down", pair), daemon=True)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for s in pair:
        try:
            s.close()
        except OSError:
            pass
    with lock:
        write_counts()


listener = socket.socket()
listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
listener.bind(("127.0.0.1", 0))
listener.listen(16)
with lock:
    write_counts()
print(listener.getsockname()[1], flush=True)
while True:
    conn, _ = listener.accept()
    threading.Thread(target=relay, args=(conn,), daemon=True).start()
