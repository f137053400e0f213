#!/usr/bin/env python3
"""End-to-end tests of `tlod play --serve` (the live dashboard, docs/play.md "Live dashboard"): frames reach an
event-stream client within a bounded time and equal trace.json's records; a client that connects and never reads
does not slow the play loop (median frame time from trace.csv and wall time per frame, with and without it) and its
dropped frames are counted; bad requests get 400/404/405, a 17th stream 503; a port in use and a bad ADDR:PORT are
clear errors before anything is played. Usage: serve_test.py TLOD DATA_DIR WORK_DIR."""
import csv, http.client, json, os, re, socket, statistics, subprocess, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tlod_cli as t

TLOD, DATA, WORK, _ = t.setup(sys.argv)
check, run = t.check, t.run


# Under ASan freed memory stays in its quarantine and counts in RSS: none, so the RSS check below measures what is
# held (other builds ignore ASAN_OPTIONS).
ENV = dict(os.environ, ASAN_OPTIONS=":".join(filter(None, [os.environ.get("ASAN_OPTIONS"), "quarantine_size_mb=0"])))


def start(out, *args):
    """tlod play on the null backend with --serve on a free port: (process, host, port) once the URL is printed."""
    p = subprocess.Popen([TLOD, "play", "--backend", "null", "-q", "--out", os.path.join(WORK, out), "--serve", "0",
                          *args], stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True, env=ENV)
    line = p.stderr.readline()
    m = re.search(r"http://([0-9.]+):([0-9]+)/", line)
    if not m:
        p.kill()
        raise SystemExit("no URL on stderr: %r" % line)
    return p, m.group(1), int(m.group(2))


def finish(p, timeout=120):
    err = p.stderr.read()
    return p.wait(timeout=timeout), err


def raw(port, request, read=65536):
    """The status code of a raw HTTP request (bytes), and the whole answer."""
    with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
        s.sendall(request)
        data = b""
        try:
            while len(data) < read:
                chunk = s.recv(65536)
                if not chunk:
                    break
                data += chunk
        except socket.timeout:
            pass
    m = re.match(rb"HTTP/1\.[01] ([0-9]{3})", data)
    return (int(m.group(1)) if m else None), data


def events(resp):
    """(event name, data text) of each server-sent event of resp, as they come."""
    name, data = "message", []
    while True:
        line = resp.readline()
        if not line:
            return
        line = line.decode().rstrip("\n")
        if not line:
            if data:
                yield name, "\n".join(data)
            name, data = "message", []
        elif line.startswith("event: "):
            name = line[7:]
        elif line.startswith("data: "):
            data.append(line[6:])


def trace_frames(out):
    return {f["frame"]: f for f in t.load_json(os.path.join(WORK, out, "trace.json"))["frames"]}


def median_frame_ms(out):
    with open(os.path.join(WORK, out, "trace.csv")) as f:
        return statistics.median(float(r["frame_ms"]) for r in csv.DictReader(f))


def summary(out):
    return t.load_json(os.path.join(WORK, out, "summary.json"))


# --- a reading client: every frame it gets is trace.json's record, the first within 5 s of connecting
p, host, port = start("live", "--frames", "3000", "--serve-linger", "3")
check("serve: loopback by default", host == "127.0.0.1", host)
conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
t0 = time.monotonic()
conn.request("GET", "/events")
resp = conn.getresponse()
check("serve: /events is an event stream", resp.status == 200 and resp.getheader("Content-Type") == "text/event-stream",
      (resp.status, resp.getheaders()))
got, first_at, run_event, end_event = [], None, None, None
for name, data in events(resp):
    if name == "run":
        run_event = json.loads(data)
    elif name == "end":
        end_event = json.loads(data)
        break
    elif name == "message":
        first_at = first_at or time.monotonic() - t0
        got.append(json.loads(data))
conn.close()
rc, err = finish(p)
check("serve: the run completes", rc == 0, err)
check("serve: the first frame arrives within 5 s", first_at is not None and first_at < 5.0, first_at)
frames = trace_frames("live")
same = [f for f in got if {k: v for k, v in f.items() if k != "dropped"} == frames.get(f["frame"])]
check("serve: every event is trace.json's record of its frame (plus 'dropped')",
      got and len(same) == len(got) and all("dropped" in f for f in got), (len(got), len(same)))
check("serve: the run event holds trace.json's settings",
      run_event and run_event["schema"] == "tlod-play-trace/2" and run_event["frames_requested"] == 3000, run_event)
dropped = end_event["dropped"] if end_event else None
check("serve: frames received + dropped = frames played (a reading client's 'dropped' is its count)",
      end_event is not None and len(got) + dropped >= 3000 - got[0]["frame"] and (not got or got[-1]["dropped"] <= dropped),
      (len(got), dropped, got[0]["frame"] if got else None))
s = summary("live").get("serve", {})
check("serve: summary.json counts the stream and the frames", s.get("streams") == 1 and s.get("frames") == 3000, s)

# --- a stuck client: connects, asks for /events, never reads (small receive buffer)
N = 6000  # frames: an unbounded queue would hold about 10 MiB of records by the end
p, _, _ = start("alone", "--frames", str(N))
rc0, err0 = finish(p)
stuck = socket.socket()
stuck.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
p, _, port = start("stuck", "--frames", str(N))
stuck.connect(("127.0.0.1", port))
stuck.sendall(b"GET /events HTTP/1.1\r\nHost: x\r\n\r\n")
t1 = time.monotonic()
rc1, err1 = finish(p, timeout=60)
stuck.close()
check("serve: a stuck client does not stop the run ending", rc0 == 0 and rc1 == 0 and time.monotonic() - t1 < 60,
      (rc0, err0, rc1, err1))
m0, m1 = median_frame_ms("alone"), median_frame_ms("stuck")
w0, w1 = summary("alone")["runs"][0]["wall_s"], summary("stuck")["runs"][0]["wall_s"]
print("median frame_ms without %.4f, with a stuck client %.4f; wall_s %.3f vs %.3f" % (m0, m1, w0, w1))
check("serve: a stuck client does not slow the frames (median frame_ms within 3x)", m1 < 3 * m0 + 0.05, (m0, m1))
check("serve: a stuck client does not slow the loop (wall time within 4x)", w1 < 4 * w0 + 1.0, (w0, w1))
r0, r1 = (summary(o)["runs"][0]["resources"][-1]["peak_rss_kib"] for o in ("alone", "stuck"))
check("serve: a stuck client's queue is bounded (peak RSS within 8 MiB of the run without it)", r1 - r0 < 8192,
      (r0, r1))
s = summary("stuck").get("serve", {})
check("serve: the stuck client's dropped frames are counted",
      s.get("streams") == 1 and s.get("dropped", 0) > N // 4 and s.get("max_dropped_per_stream") == s.get("dropped"), s)

# --- bad requests, the page, run.json, at most 16 streams, the port taken
p, _, port = start("requests", "--frames", "5", "--serve-linger", "20")
code, body = raw(port, b"GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", read=1 << 22)
check("serve: GET / is the dashboard page in live mode (its config names /events)",
      code == 200 and b"text/html" in body and re.search(rb'"live":\s*"/events"', body) and b"uPlot" in body,
      body[:300])
for _ in range(100):  # {"status": "starting"} until the first mode starts
    code, body = raw(port, b"GET /run.json HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
    meta = json.loads(body.split(b"\r\n\r\n", 1)[1]) if code == 200 else {}
    if meta.get("status") != "starting":
        break
    time.sleep(0.1)
check("serve: /run.json is the run's settings", meta.get("scene") == "demo:scene" and meta.get("backend") == "null",
      body[:300])
for name, req, want in [
        ("404: unknown path", b"GET /etc/passwd HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", 404),
        ("404: a path below a file", b"GET /run.json/x HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", 404),
        ("405: POST", b"POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\nConnection: close\r\n\r\n", 405),
        ("405: DELETE /events", b"DELETE /events HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", 405),
        ("400: a GET with a body", b"GET / HTTP/1.1\r\nHost: x\r\nContent-Length: 5\r\nConnection: close\r\n\r\nhello",
         400),
        ("400: not HTTP", b"HELLO THERE\r\n\r\n", 400),
        ("400: HTTP/1.1 without Host", b"GET / HTTP/1.1\r\nConnection: close\r\n\r\n", 400),
        ("400: an absolute URI", b"GET http://evil.example/ HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n", 400)]:
    code, body = raw(port, req)
    check("serve: " + name, code == want, (code, body[:200]))
code, body = raw(port, b"POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\nConnection: close\r\n\r\n")
check("serve: 405 says what is allowed", b"Allow: GET, HEAD" in body, body[:300])
streams = []
for k in range(16):
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    c.request("GET", "/events")
    streams.append((c, c.getresponse()))
check("serve: 16 streams at once", all(r.status == 200 for _, r in streams), [r.status for _, r in streams])
code, body = raw(port, b"GET /events HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
check("serve: a 17th stream is 503", code == 503, (code, body[:200]))
other = os.path.join(WORK, "second")
rc, out, err = run("play", "--backend", "null", "--frames", "5", "--out", other, "--serve", "127.0.0.1:%d" % port)
check("serve: a port in use is one clear error, before any run folder", rc == 1 and t.one_error_line(err) and
      "--serve 127.0.0.1:%d: cannot listen: Address already in use" % port in err and not os.path.exists(other),
      (rc, err))
for c, _ in streams:
    c.close()
p.send_signal(2)  # Ctrl-C ends --serve-linger
rc, err = finish(p)
check("serve: Ctrl-C ends the linger; the server stops with 16 streams open", rc == 0, (rc, err))
s = summary("requests").get("serve", {})
check("serve: summary.json counts the streams and the refused one", s.get("streams") == 16 and s.get("refused") == 1, s)

# --- bad --serve values: usage errors, nothing played
for value, problem in [("abc", "expected [ADDR:]PORT"), ("70000", "PORT 0..65535"), ("1.2.3:80", "IPv4"),
                       ("example.com:80", "IPv4"), (":80", "IPv4"), ("127.0.0.1:", "expected [ADDR:]PORT")]:
    out_dir = os.path.join(WORK, "bad")
    rc, out, err = run("play", "--backend", "null", "--frames", "2", "--out", out_dir, "--serve", value)
    check("serve: --serve %s is a usage error" % value,
          rc == 2 and t.one_error_line(err) and problem in err and not os.path.exists(out_dir), (rc, err))
rc, out, err = run("play", "--backend", "null", "--frames", "2", "--serve-linger", "-1")
check("serve: --serve-linger -1 is a usage error", rc == 2 and t.one_error_line(err), (rc, err))
rc, out, err = run("play", "--backend", "null", "--frames", "2", "--serve-linger", "1")
check("serve: --serve-linger without --serve is a usage error", rc == 2 and "needs --serve" in err, (rc, err))

t.finish()
