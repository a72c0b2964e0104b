"""`floorgrid serve` under hostile loads (issue 31), one after another, with the server's memory.

Starts `floorgrid serve ALIGN_DIR --port 0`, waits for it, notes its resident memory with the
model loaded, then for each load resets its peak (/proc/PID/clear_refs 5), drives the load and
prints what the clients saw and the server's peak (VmHWM) above that baseline:

  slow-headers   40 connections each sending a header line every 2 s for 30 s, while another
                 client asks GET /api/info every second (its slowest answer)
  chunked-bomb   300 MB POSTed to /api/map chunked, then 300 MB with no length at all
  invalid-utf8   the paths of the issue (%ff, %c3%28, DELETE /api/pairs/%ff, %c0%ae, a NUL, a
                 query of %ff) and one of raw bytes
  million-points 4 POST /api/map of 1,000,000 points at once, then 8 at once, while another
                 client asks GET /api/info every half second
  million-points-1  one such request alone (not run by default)

Usage: viewer_hostile.py FLOORGRID_BINARY ALIGN_DIR [LOAD ...]
"""

import json
import os
import random
import re
import socket
import subprocess
import sys
import threading
import time


def memory_kb(pid, field):
    with open(f"/proc/{pid}/status") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


def reset_peak(pid):
    with open(f"/proc/{pid}/clear_refs", "w") as refs:
        refs.write("5")


def connect(port, timeout=60.0):
    s = socket.create_connection(("127.0.0.1", port), timeout=timeout)
    s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return s


def read_answer(s, count_of=None, keep=4096):
    """Reads until the server closes: (status, first bytes, bytes, occurrences of count_of)."""
    head, total, count, tail = b"", 0, 0, b""
    while True:
        try:
            block = s.recv(1 << 16)
        except (socket.timeout, ConnectionResetError):
            break
        if not block:
            break
        total += len(block)
        if len(head) < keep:
            head += block[: keep - len(head)]
        if count_of:
            text = tail + block
            count += text.count(count_of)
            tail = text[-(len(count_of) - 1):]
    match = re.match(rb"HTTP/1\.\d (\d+)", head)
    return (int(match.group(1)) if match else 0), head, total, count


def request(port, raw, timeout=60.0):
    s = connect(port, timeout)
    try:
        s.sendall(raw)
        return read_answer(s)
    finally:
        s.close()


def get(port, path, timeout=60.0):
    return request(port, f"GET {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n".encode(),
                   timeout)


def body_of(head):
    return head.split(b"\r\n\r\n", 1)[1] if b"\r\n\r\n" in head else b""


def load_slow_headers(port, pid):
    closed_after = []
    stop = threading.Event()
    started = time.monotonic()

    def slow():
        try:
            s = connect(port, 5.0)
            s.sendall(b"GET /api/info HTTP/1.1\r\nHost: x\r\n")
            for line in range(15):
                s.settimeout(2.0)
                try:
                    if s.recv(1 << 16) is not None:  # an answer or the close: given up on
                        closed_after.append(time.monotonic() - started)
                        return
                except socket.timeout:
                    pass
                if stop.is_set():
                    return
                s.sendall(f"X-Slow-{line}: 1\r\n".encode())
        except OSError:
            closed_after.append(time.monotonic() - started)

    threads = [threading.Thread(target=slow) for _ in range(40)]
    for t in threads:
        t.start()
    time.sleep(1.0)
    waits, failures = [], 0
    while time.monotonic() - started < 30.0:
        asked = time.monotonic()
        try:
            status, _, _, _ = get(port, "/api/info", timeout=30.0)
        except OSError:
            status = 0
        waits.append(time.monotonic() - asked)
        failures += status != 200
        time.sleep(max(0.0, 1.0 - waits[-1]))
    stop.set()
    for t in threads:
        t.join()
    dropped = sorted(closed_after)
    print(f"  /api/info asked {len(waits)} times during the load: slowest {max(waits):.3f} s, "
          f"{failures} not 200")
    print(f"  slow connections dropped by the server: {len(dropped)} of 40"
          + (f", after {dropped[0]:.1f} to {dropped[-1]:.1f} s" if dropped else ""))


def load_chunked_bomb(port, pid):
    for kind in ("chunked", "no length"):
        s = connect(port)
        head = b"POST /api/map HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
        head += b"Transfer-Encoding: chunked\r\n\r\n" if kind == "chunked" else b"\r\n"
        s.sendall(head)
        block = b" " * (1 << 20)
        frame = (b"%x\r\n" % len(block)) + block + b"\r\n" if kind == "chunked" else block
        sent, started = 0, time.monotonic()
        try:
            while sent < 300_000_000:
                s.sendall(frame)
                sent += len(block)
        except OSError:
            pass
        if kind == "chunked" and sent >= 300_000_000:
            try:
                s.sendall(b"0\r\n\r\n")
            except OSError:
                pass
        if kind == "no length":
            try:
                s.shutdown(socket.SHUT_WR)
            except OSError:
                pass
        s.settimeout(30.0)
        status, head, _, _ = read_answer(s)
        s.close()
        print(f"  {kind}: {sent / 1e6:.0f} MB sent by the client before it had the answer, "
              f"answer {status} {body_of(head)[:120].decode(errors='replace')} "
              f"({time.monotonic() - started:.2f} s)")


def load_invalid_utf8(port, pid):
    lines = [b"GET /%ff", b"GET /api/%c3%28", b"DELETE /api/pairs/%ff",
             b"GET /%c0%ae%c0%ae/%c0%ae%c0%ae/etc/passwd", b"GET /api/heatmap.png?kind=%ff",
             b"GET /index.html%00.png", b"GET /\xff\xfe", b"POST /api/%ff"]
    for line in lines:
        try:
            status, head, _, _ = request(
                port,
                line + b" HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: 0\r\n\r\n")
        except OSError as e:
            print(f"  {line.decode('latin-1')!r:48} -> no connection ({e.strerror}): the server is gone")
            return
        raw = any(b >= 0x80 for b in head)
        print(f"  {line.decode('latin-1')!r:48} -> {status} {body_of(head)[:90].decode('latin-1')}"
              + ("  RAW BYTES ECHOED" if raw else ""))
    try:
        status, _, _, _ = get(port, "/api/info")
    except OSError as e:
        status = e.strerror
    print(f"  then GET /api/info -> {status}")


def million_points_body(bounds, n, seed):
    rng = random.Random(seed)
    (x0, y0), (x1, y1) = bounds
    points = ",".join(f"[{rng.randint(int(x0), int(x1))},{rng.randint(int(y0), int(y1))}]"
                      for _ in range(n))
    return ('{"from": "plan", "points": [' + points + "]}").encode()


def load_million_points(port, pid, bounds, counts):
    body = million_points_body(bounds, 1_000_000, 1)
    raw = (b"POST /api/map HTTP/1.1\r\nHost: x\r\nConnection: close\r\n"
           b"Content-Type: application/json\r\nContent-Length: %d\r\n\r\n" % len(body)) + body
    print(f"  each request: 1,000,000 points, a {len(body) / 1e6:.1f} MB body")
    for at_once in counts:
        reset_peak(pid)
        results = [None] * at_once
        waits = []
        done = threading.Event()

        def ask_info():
            while not done.is_set():
                asked = time.monotonic()
                status, _, _, _ = get(port, "/api/info", timeout=60.0)
                waits.append((time.monotonic() - asked, status))
                done.wait(0.5)

        def one(k):
            started = time.monotonic()
            s = connect(port, 600.0)
            s.sendall(raw)
            status, head, total, count = read_answer(s, b'"flag"')
            s.close()
            results[k] = (status, total, count, time.monotonic() - started,
                          body_of(head)[:100].decode(errors="replace"))

        threads = [threading.Thread(target=one, args=(k,)) for k in range(at_once)]
        info = threading.Thread(target=ask_info)
        started = time.monotonic()
        for t in threads:
            t.start()
        info.start()
        for t in threads:
            t.join()
        done.set()
        info.join()
        print(f"  {at_once} at once ({time.monotonic() - started:.1f} s; meanwhile /api/info "
              f"asked {len(waits)} times, slowest {max(w for w, _ in waits):.3f} s, "
              f"{sum(s != 200 for _, s in waits)} not 200):")
        for status, total, count, seconds, text in results:
            what = f"{count:,} points, {total / 1e6:.0f} MB" if status == 200 else text
            print(f"    {status}: {what} in {seconds:.1f} s")
        print(f"    server peak {memory_kb(pid, 'VmHWM') / 1024:.0f} MiB "
              f"(now {memory_kb(pid, 'VmRSS') / 1024:.0f} MiB)")


def main():
    binary, align = sys.argv[1], sys.argv[2]
    loads = sys.argv[3:] or ["slow-headers", "chunked-bomb", "invalid-utf8", "million-points"]
    log = open(os.path.join(os.path.dirname(os.path.abspath(align)), "serve-hostile.log"), "w+")
    server = subprocess.Popen([binary, "serve", align, "--port", "0"], stdout=log,
                              stderr=subprocess.STDOUT)
    try:
        port = None
        for _ in range(600):
            log.seek(0)
            match = re.search(r"at http://[^:]+:(\d+)/", log.read())
            if match:
                port = int(match.group(1))
                break
            if server.poll() is not None:
                sys.exit(f"serve exited with {server.returncode}")
            time.sleep(0.1)
        if port is None:
            sys.exit("serve did not start")
        info = json.loads(body_of(get(port, "/api/info")[1]))
        pid = server.pid
        baseline = memory_kb(pid, "VmRSS")
        print(f"serve pid {pid} on port {port}: model {info['model']}, {baseline / 1024:.0f} MiB "
              f"resident with the model loaded (VmRSS)")
        for load in loads:
            print(f"== {load}")
            reset_peak(pid)
            started = time.monotonic()
            if load == "slow-headers":
                load_slow_headers(port, pid)
            elif load == "chunked-bomb":
                load_chunked_bomb(port, pid)
            elif load == "invalid-utf8":
                load_invalid_utf8(port, pid)
            elif load == "million-points":
                load_million_points(port, pid, info["plan"]["bounds"], (4, 8))
            elif load == "million-points-1":
                load_million_points(port, pid, info["plan"]["bounds"], (1,))
            time.sleep(0.2)  # a server that died of the load: its status known
            alive = server.poll() is None
            if not alive:
                print(f"  server EXITED (status {server.returncode}) "
                      f"({time.monotonic() - started:.1f} s)")
                break
            peak = memory_kb(pid, "VmHWM")
            print(f"  server still answering; peak over the load {peak / 1024:.0f} MiB, "
                  f"{(peak - baseline) / 1024:+.0f} MiB above the loaded model "
                  f"({time.monotonic() - started:.1f} s)")
    finally:
        server.terminate()
        server.wait()


if __name__ == "__main__":
    main()
