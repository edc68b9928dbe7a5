"""``gear3d serve``: the JSON API (in-process ASGI calls) and the page in a real browser.

The browser tests drive Debian's Chromium (``/usr/bin/chromium``; CI's ``.ci/run`` installs
it) with Playwright against ``gear3d serve`` started as a subprocess on a free port. They
fail (never skip) when Chromium or Playwright is missing. Oracles: the CLI's own bytes and
messages, the involute tip radius m(z/2 + 1), trimesh's watertightness, seed 001's area B.
"""
from __future__ import annotations

import asyncio
import functools
import io
import json
import os
import re
import socket
import subprocess
import sys
import threading
import urllib.request
from pathlib import Path

import pytest

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--no-first-run", "--disable-sync"]
ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "out" / "web"
#: a ceiling for each page action, not a timing assert: a shared 2-core machine under the
#: whole suite can take tens of seconds for one build (a crossed pair, a face gear set)
TIMEOUT_MS = 150_000


# ------------------------------------------------------------------ in-process API (no server)

def _asgi_get(app, path: str, query: str = ""):
    """(status, headers dict, body bytes) of one GET through the ASGI app."""
    sent = []

    async def receive():
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(msg):
        sent.append(msg)

    scope = {"type": "http", "asgi": {"version": "3.0"}, "http_version": "1.1", "method": "GET",
             "scheme": "http", "path": path, "raw_path": path.encode(), "query_string": query.encode(),
             "root_path": "", "headers": [(b"host", b"test")], "client": ("127.0.0.1", 1),
             "server": ("test", 80)}
    asyncio.run(app(scope, receive, send))
    start = next(m for m in sent if m["type"] == "http.response.start")
    body = b"".join(m.get("body", b"") for m in sent if m["type"] == "http.response.body")
    return start["status"], {k.decode().lower(): v.decode() for k, v in start["headers"]}, body


def _strict(body: bytes):
    def bad(c):
        raise AssertionError(f"non-strict JSON constant {c}")
    return json.loads(body, parse_constant=bad)


@pytest.fixture(scope="module")
def app():
    from gear3d.web.app import create_app
    return create_app(max_builds=1, log=io.StringIO())


def test_schema_from_signatures_and_cli_flags(app):
    import inspect

    from gear3d.profiles import FAMILIES
    st, _, body = _asgi_get(app, "/api/families")
    fams = _strict(body)["families"]
    assert st == 200 and "involute" in fams and "sine" in fams and "mate" not in fams   # mate takes a Profile
    for fam in ("involute", "sine", "cycloid-disc"):
        st, _, body = _asgi_get(app, f"/api/schema/{fam}")
        sch = _strict(body)
        sig = {k: p.default for k, p in inspect.signature(FAMILIES[fam]).parameters.items() if p.kind is not p.VAR_KEYWORD}
        assert [f["name"] for f in sch["profile"]] == list(sig)
        for f in sch["profile"]:
            if f["name"] != "tolerance":           # the CLI picks it by output
                assert f["default"] == sig[f["name"]]
    inv = {f["name"]: f for f in _strict(_asgi_get(app, "/api/schema/involute")[2])["profile"]}
    assert inv["teeth"]["flag"] == "--teeth" and inv["teeth"]["type"] == "int"
    assert inv["module"]["unit"] == "mm" and inv["pressure_angle_deg"]["unit"] == "deg"
    assert inv["internal"]["type"] == "bool"
    body = {f["name"]: f for f in _strict(_asgi_get(app, "/api/schema/involute")[2])["body"]}
    assert body["kind"]["choices"] == ["spur", "helical", "herringbone", "chevron-arch"]
    assert body["width"]["required"] is True
    assert _asgi_get(app, "/api/schema/nope")[0] == 400


def test_bad_input_is_the_clis_message_and_never_a_path(app, capsys):
    from gear3d.cli import main
    st, _, body = _asgi_get(app, "/api/profile", "family=involute&teeth=0")
    err = _strict(body)
    assert st == 400 and err["param"] == "teeth" and "teeth" in err["error"]
    assert main(["profile", "involute", "--teeth", "0"]) == 2
    cli_line = capsys.readouterr().err.strip()
    assert "\n" not in cli_line and err["allowed"] in cli_line       # the CLI states the same range
    st, _, body = _asgi_get(app, "/api/download", "family=involute&fmt=stl&output=/etc/passwd")
    assert st == 400 and _strict(body)["param"] == "output"
    st, _, body = _asgi_get(app, "/api/download", "family=involute&fmt=exe")
    assert st == 400 and _strict(body)["param"] == "fmt"
    st, _, body = _asgi_get(app, "/api/profile", "family=involute&teeth=abc")
    assert st == 400 and _strict(body)["param"] == "teeth"
    assert b"Traceback" not in body


def test_busy_answers_503_and_the_budget_refuses_before_building(app, monkeypatch, tmp_path):
    import gear3d.solids.body as solids_body
    slots = app.state.slots
    assert slots.sem.acquire(blocking=False)          # one build running (max_builds=1)
    try:
        st, _, body = _asgi_get(app, "/api/profile", "family=involute&teeth=20")
        assert st == 503 and "busy" in _strict(body)["error"]
    finally:
        slots.sem.release()
    st, _, body = _asgi_get(app, "/api/profile", "family=involute&teeth=20")
    assert st == 200
    calls, real = [], solids_body.body

    @functools.wraps(real)
    def spy(*a, **k):
        calls.append(1)
        return real(*a, **k)
    monkeypatch.setattr(solids_body, "body", spy)
    st, _, body = _asgi_get(app, "/api/download", "family=involute&teeth=50000&b.width=100&tolerance=0.001&fmt=stl")
    err = _strict(body)
    assert st == 400 and err["param"] == "teeth" and "budget" in err["error"] and not calls
    from gear3d.cli import main
    out = tmp_path / "big.stl"
    assert main(["body", "involute", "--teeth", "50000", "--width", "100", "--tolerance", "0.001", "-o", str(out)]) == 2
    assert not out.exists()                           # the CLI refuses it too (the same budget)
    st, _, body = _asgi_get(app, "/api/pair", "family=involute&teeth=3000&pair.mate_teeth=3001&tolerance=0.001")
    assert st == 400 and "budget" in _strict(body)["error"]


@pytest.mark.parametrize("fmt, cmd", [("3mf", "body"), ("dxf", "profile")])     # STL: in the browser below
def test_downloads_are_the_clis_bytes(app, tmp_path, capsys, fmt, cmd):
    from gear3d.cli import main
    flags = ["--teeth", "18", "--tolerance", "0.01"] + (["--width", "4"] if cmd == "body" else [])
    st, head, data = _asgi_get(app, "/api/download", f"family=involute&teeth=18&tolerance=0.01&b.width=4&fmt={fmt}")
    assert st == 200, data[:300]
    assert head["content-disposition"] == f'attachment; filename="involute-z18{"-body" if cmd == "body" else ""}.{fmt}"'
    out = tmp_path / f"cli.{fmt}"
    assert main([cmd, "involute", *flags, "-o", str(out)]) == 0
    capsys.readouterr()
    assert data == out.read_bytes()


def test_strict_json_and_binary_mesh():
    from types import SimpleNamespace

    from gear3d.web import strict
    from gear3d.web.meshdata import decode, encode
    assert _strict(strict.dumps({"a": float("nan"), "b": [float("inf"), 1.5]}).encode()) == {"a": None, "b": [None, 1.5]}
    tet = SimpleNamespace(mesh=SimpleNamespace(vertices=[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                                               faces=[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    V, F = decode(encode([tet, tet]))
    assert V.shape == (8, 3) and F.shape == (8, 3) and F[4:].min() == 4 and V[5, 0] == 1.0


@pytest.mark.parametrize("kind, extra", [("spur", ""), ("helical", "&b.helix_angle_deg=20"),
                                         ("herringbone", "&b.helix_angle_deg=20"),
                                         ("chevron-arch", "&b.helix_angle_deg=30&b.arch_radius=4")])
def test_body_preview_every_kind_is_a_closed_mesh(app, kind, extra):
    import numpy as np
    import trimesh

    from gear3d.web.meshdata import decode
    st, head, blob = _asgi_get(app, "/api/body", f"family=involute&teeth=20&tolerance=0.05&b.width=6&b.kind={kind}{extra}")
    assert st == 200, blob[:300]
    V, F = decode(blob)
    rep = _strict(head["x-gear3d-report"].encode())
    assert rep["kind"] == kind and rep["triangles"] == len(F) and rep["tolerance"] >= 0.01
    mesh = trimesh.Trimesh(np.asarray(V, float), np.asarray(F, np.int64), process=True)
    assert mesh.is_watertight
    assert abs(mesh.bounds[1, 2] - mesh.bounds[0, 2] - 6.0) < 1e-4
    assert abs(np.hypot(V[:, 0], V[:, 1]).max() - 11.0) < 0.06      # tip radius m (z/2 + 1)


def test_profile_svg_marks_undercut_and_pointing():
    import gear3d
    from gear3d.web.svg import neck, profile_svg
    under = gear3d.profile("involute", teeth=8, tip_radius_coeff=0)       # z < 17: undercut
    assert under.report["undercut"]
    s = profile_svg(under)
    assert 'class="undercut"' in s and 'class="neck"' in s and neck(under)["thickness"] < neck(under)["thicker_outside"]
    pointed = gear3d.profile("sine", teeth=20, addendum_coeff=1.5)          # seed 001: pointed from 1.5
    assert 'class="pointed-tip"' in profile_svg(pointed)
    plain = profile_svg(gear3d.profile("involute", teeth=30))
    for c in ("pitch-circle", "base-circle", "root-circle", "tip-circle"):
        assert f'class="{c}"' in plain
    assert 'class="undercut"' not in plain and "pointed-tip" not in plain


def test_serve_refuses_a_busy_port_in_one_line(capsys):
    from gear3d.cli import main
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        assert main(["serve", "--port", str(port)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"port = {port} is not allowed" in err and "[0, 65535]" in err


# ------------------------------------------------------------------ the page in Chromium

class _Lines:
    """The lines of one output stream of a child, read as they come by a thread (which also
    keeps the pipe drained) and copied to ``copy`` (a file kept for a failing run's log).
    :meth:`wait` blocks on a condition until a line matches; no polling."""

    def __init__(self, stream, copy: Path):
        self.lines, self.closed = [], False
        self._cond = threading.Condition()
        self._thread = threading.Thread(target=self._read, args=(stream, copy), daemon=True)
        self._thread.start()

    def _read(self, stream, copy):
        with open(copy, "w") as f:
            for line in stream:
                f.write(line)
                f.flush()
                with self._cond:
                    self.lines.append(line.rstrip("\n"))
                    self._cond.notify_all()
        with self._cond:
            self.closed = True          # EOF: the child closed it (it exited)
            self._cond.notify_all()

    def text(self) -> str:
        with self._cond:
            return "\n".join(self.lines)

    def wait(self, pattern: re.Pattern, timeout: float):
        """The first match of ``pattern`` in a line; None once the stream closed or after
        ``timeout`` seconds without one."""
        def found():
            return next((m for m in map(pattern.search, self.lines) if m), None)
        with self._cond:
            self._cond.wait_for(lambda: found() or self.closed, timeout)
            return found()

    def join(self, timeout: float):
        self._thread.join(timeout)


class _Server:
    """``gear3d serve --port 0`` as a subprocess: the kernel picks a free port and the server
    prints its URL once its socket listens; :meth:`ready` waits for that line."""

    def __init__(self, d: Path):
        self.proc = subprocess.Popen([sys.executable, "-m", "gear3d.cli", "serve", "--port", "0",
                                      "--max-builds", "3"], cwd=d, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
        self.out = _Lines(self.proc.stdout, d / "serve.out")
        self.log = _Lines(self.proc.stderr, d / "serve.log")      # one line a request
        self.url = None

    def ready(self, timeout: float = 90.0) -> "_Server":
        if self.url is None:
            m = self.out.wait(re.compile(r"^gear3d serve: (http://127\.0\.0\.1:\d+)/ "), timeout)
            if m is None:
                code = self.proc.poll()
                pytest.fail((f"gear3d serve exited with {code}" if code is not None else
                             f"gear3d serve printed no URL within {timeout:g} s") + f": {self.log.text()[-2000:]}")
            self.url = m.group(1)
            # the socket listens: this request waits in its backlog until the server answers
            with urllib.request.urlopen(self.url + "/api/families", timeout=timeout) as r:
                assert r.status == 200
        return self

    def stop(self):
        self.proc.terminate()
        try:
            self.proc.wait(15)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait(5)
        self.out.join(5)
        self.log.join(5)


def _launch(pw):
    """Debian's Chromium under Playwright; a clear failure (never a skip) when it is missing."""
    if not os.path.exists(CHROMIUM):
        pytest.fail(f"{CHROMIUM} not found: the browser test needs Debian's Chromium "
                    "(apt-get install -y chromium; CI's .ci/run installs it)")
    return pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)


def test_page_in_chromium(tmp_path, capsys):
    """The page in a real browser, one server and one browser for all the steps (so that a
    parallel run, pytest -n, keeps them in one worker): the SVG follows the teeth, a bad value
    shows its message next to the field, the STL download is the CLI's bytes and watertight,
    a pair with interference is drawn red, a screenshot is kept, each request logged."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        pytest.fail("playwright is not installed: pip install -e '.[test]'")
    (tmp_path / "serve").mkdir()
    server = _Server(tmp_path / "serve")          # starts while the browser launches
    try:
        with sync_playwright() as pw:
            browser = _launch(pw)
            try:
                server.ready()
                ctx = browser.new_context(viewport={"width": 1400, "height": 1000}, accept_downloads=True)
                page = ctx.new_page()
                page.set_default_timeout(TIMEOUT_MS)
                errors = []
                page.on("pageerror", lambda e: errors.append(str(e)))
                page.goto(server.url + "/")
                page.wait_for_selector("body[data-ready='1'] #preview svg.gear3d-preview")
                _check_preview_follows_the_teeth(page)
                _check_bad_value_next_to_the_field(page)
                _check_stl_download_is_the_clis_bytes(page, tmp_path, capsys)
                _check_pair_interference_drawn_red(page)
                _check_worm_and_bevel(page, tmp_path, capsys)
                assert not errors, errors
            finally:
                browser.close()
        _check_one_log_line_a_request(server)
    finally:
        server.stop()


def _profile_points(svg_d: str):
    """(n, 2) points of the preview's profile path (mm; the SVG flips y)."""
    import numpy as np
    nums = [float(x) for x in re.findall(r"-?\d+\.?\d*(?:e-?\d+)?", svg_d)]
    return np.array(nums).reshape(-1, 2)


def _check_preview_follows_the_teeth(page):
    import numpy as np
    before = page.get_attribute("#preview svg.gear3d-preview", "data-teeth")
    assert before == "20"
    page.fill("#in-profile-teeth", "13")
    page.wait_for_selector("#preview svg.gear3d-preview[data-teeth='13']")
    pts = _profile_points(page.get_attribute("#preview svg .full path.profile", "d"))
    r = np.hypot(pts[:, 0], pts[:, 1])
    assert abs(r.max() - 1.0 * (13 / 2 + 1)) < 2e-3          # involute tip radius m (z/2 + 1)
    assert abs(float(page.get_attribute("#preview svg .full circle.pitch-circle", "r")) - 6.5) < 1e-6
    # the report names what the SVG shows
    assert "7.5 mm" in page.inner_text("#report")
    page.fill("#in-profile-teeth", "20")
    page.wait_for_selector("#preview svg.gear3d-preview[data-teeth='20']")


def _check_bad_value_next_to_the_field(page):
    page.fill("#in-profile-teeth", "0")
    err = page.locator("#field-profile-teeth .error")
    err.wait_for(state="visible")
    text = err.inner_text()
    assert "teeth" in text and "[1, 100000]" in text
    assert "invalid" in page.get_attribute("#field-profile-teeth", "class")
    assert "Traceback" not in page.content()
    page.fill("#in-profile-teeth", "20")
    page.wait_for_selector("#field-profile-teeth .error:empty", state="attached")
    page.wait_for_selector("#preview svg.gear3d-preview[data-teeth='20']")


def _check_stl_download_is_the_clis_bytes(page, tmp_path, capsys):
    import trimesh

    from gear3d.cli import main
    page.fill("#in-profile-tolerance", "0.01")
    page.fill("#in-body-width", "5")
    with page.expect_download(timeout=TIMEOUT_MS) as dl:
        page.click("#download-stl")
    web = tmp_path / "web.stl"
    dl.value.save_as(web)
    assert dl.value.suggested_filename == "involute-z20-body.stl"
    cli = tmp_path / "cli.stl"
    assert main(["body", "involute", "--teeth", "20", "--width", "5", "--tolerance", "0.01", "-o", str(cli)]) == 0
    capsys.readouterr()
    assert web.read_bytes() == cli.read_bytes()
    mesh = trimesh.load(web, file_type="stl")
    assert mesh.is_watertight and len(mesh.faces) > 1000
    assert abs(mesh.bounds[1, 2] - mesh.bounds[0, 2] - 5.0) < 1e-4


def _check_pair_interference_drawn_red(page):
    import numpy as np
    from PIL import Image
    page.select_option("#family", "sine")
    page.wait_for_selector("body[data-family='sine'] #in-profile-addendum_coeff")
    page.fill("#in-profile-addendum_coeff", "1")
    page.fill("#in-profile-tolerance", "0.01")
    page.check("#in-profile-internal")
    page.fill("#in-pair-mate_teeth", "21")
    page.click("#check-pair")
    page.wait_for_selector("#pair-summary.bad", timeout=120_000)      # seed 001 area B: z20 in z21 at c_h = 1
    summary = page.inner_text("#pair-summary")
    assert summary.startswith("INTERFERENCE") and "opposite the pitch point" in summary
    assert "opposite the pitch point" in page.inner_text("#pair-report")
    page.click("#pair-play")                                          # pause on the worst frame
    page.fill("#pair-frame", "0")
    assert page.locator("#pair-view path.interference").count() > 0
    png = page.locator("#pair-view").screenshot()
    rgb = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)
    red = (rgb[..., 0] > 200) & (rgb[..., 1] < 70) & (rgb[..., 2] < 70)
    assert red.sum() > 300, f"only {red.sum()} red pixels in the pair view"
    # the screenshot people look at: wait for the 3D body of this ring too
    page.wait_for_selector("#view3d[data-family='sine'][data-internal='true']")
    OUT.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(OUT / "page.png"), full_page=True)
    assert (OUT / "page.png").stat().st_size > 10_000


def _check_worm_and_bevel(page, tmp_path, capsys):
    """The sets: one form, the wheel's mid-plane section (its throat radius m (z2/2 + 1)) or
    the bevel gear's heel section (pitch radius m z1 / 2) drawn, the set's own downloads, an
    STL that is the CLI's bytes."""
    import numpy as np

    from gear3d.cli import main

    def drawn_radius(cls="profile"):
        pts = _profile_points(page.get_attribute(f"#preview svg .full path.{cls}", "d"))
        return np.hypot(pts[:, 0], pts[:, 1]).max()
    page.select_option("#family", "worm")
    page.wait_for_selector("body[data-family='worm'] #preview svg.gear3d-preview[data-teeth='30']")
    assert page.is_hidden("#section-body") and page.is_hidden("#section-pair") and page.is_hidden("#pair-panel")
    assert page.is_visible("#download-dxf") and page.is_hidden("#download-svg")
    assert abs(drawn_radius() - 2.0 * (30 / 2 + 1)) < 2e-3
    assert "wheel mid-plane section" in page.inner_text("#report")
    page.fill("#in-profile-wheel_teeth", "24")
    page.select_option("#in-profile-part", "wheel")
    page.wait_for_selector("#preview svg.gear3d-preview[data-teeth='24']")
    page.wait_for_selector("#view3d[data-family='worm'][data-triangles]")
    _stl_download_is_the_cli_s(page, tmp_path, capsys, main, "worm-z24-wheel.stl",
                               ["worm", "--module", "2", "--starts", "1", "--wheel-teeth", "24", "--part", "wheel"])
    OUT.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(OUT / "worm.png"), full_page=True)
    page.select_option("#family", "bevel")
    page.wait_for_selector("body[data-family='bevel'] #preview svg.gear3d-preview[data-teeth='20']")
    assert abs(float(page.get_attribute("#preview svg .full circle.pitch-circle", "r")) - 2.0 * 20 / 2) < 1e-6
    assert page.is_visible("#download-step") and page.is_hidden("#download-dxf")
    _stl_download_is_the_cli_s(page, tmp_path, capsys, main, "bevel-z20-gear.stl",
                               ["bevel", "--teeth", "20", "--mate-teeth", "40", "--module", "2"])
    _check_face_gear(page, tmp_path, capsys, main)
    _check_crossed(page, tmp_path, capsys, main)
    page.select_option("#family", "involute")
    page.wait_for_selector("body[data-family='involute'] #preview svg.gear3d-preview")
    assert page.is_visible("#section-body") and page.is_visible("#download-svg")


def _check_face_gear(page, tmp_path, capsys, main):
    """The face gear set: its sections drawn, its own downloads (JSON, no DXF), an STL that is
    ``gear3d face-gear``'s bytes for the form's defaults (40 teeth, the page's 20-tooth shaper)."""
    page.select_option("#family", "face-gear")
    page.wait_for_selector("body[data-family='face-gear'] #preview svg.gear3d-preview[data-teeth='40']")
    assert page.is_visible("#download-json") and page.is_hidden("#download-dxf")
    _stl_download_is_the_cli_s(page, tmp_path, capsys, main, "face-gear-z40-gear.stl",
                               ["face-gear", "--teeth", "40", "--shaper-teeth", "20", "--module", "1"])


def _check_crossed(page, tmp_path, capsys, main):
    """The crossed helical pair: wheel 1's transverse section drawn (pitch radius
    z1 m_n / (2 cos b1)), the pair's centre distance m_n/2 (z1/cos b1 + z2/cos b2) and its
    check in the report, an STL of both gears that is ``gear3d check pair --crossed``'s bytes."""
    import math
    page.select_option("#family", "crossed")
    page.wait_for_selector("body[data-family='crossed'] #preview svg.gear3d-preview[data-teeth='12']")
    c45 = math.cos(math.radians(45))
    assert abs(float(page.get_attribute("#preview svg .full circle.pitch-circle", "r")) - 12 / (2 * c45)) < 1e-5
    report = page.inner_text("#report")
    assert f"{(12 + 14) / (2 * c45):.5g} mm" in report and "check: contact ratio" in report
    assert page.is_visible("#download-step") and page.is_hidden("#download-json")
    _stl_download_is_the_cli_s(page, tmp_path, capsys, main, "crossed-z12-pair.stl",
                               ["check", "pair", "involute", "--crossed", "--teeth", "12", "--mate-teeth", "14",
                                "--module", "1", "--helix-angle-deg", "45", "--width", "6"])


def _stl_download_is_the_cli_s(page, tmp_path, capsys, main, name, argv):
    """The page's STL download is named ``name`` and holds the bytes ``gear3d ARGV -o x.stl``
    writes."""
    with page.expect_download(timeout=TIMEOUT_MS) as dl:
        page.click("#download-stl")
    web = tmp_path / ("web-" + name)
    dl.value.save_as(web)
    assert dl.value.suggested_filename == name
    cli = tmp_path / ("cli-" + name)
    assert main([*argv, "-o", str(cli)]) == 0
    capsys.readouterr()
    assert web.read_bytes() == cli.read_bytes()


def _check_one_log_line_a_request(server):
    url, log = server.url, server.log
    with urllib.request.urlopen(url + "/api/profile?family=involute&teeth=17", timeout=30) as r:
        assert r.status == 200
    # the line is written once the answer is sent: wait for it on the server's stderr
    pat = re.compile(r"^\d\d:\d\d:\d\d 127\.0\.0\.1 GET /api/profile\?family=involute&teeth=17 200 \d+ ms$")
    assert log.wait(pat, timeout=10), log.text()[-1000:]
    assert "Traceback" not in log.text()
