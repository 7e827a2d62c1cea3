"""End-to-end test of `layertrace serve`: headless Chromium drives the page.

Run by .ci/run (pytest, Python's playwright pointed at the system's Chromium with
executable_path: playwright downloads no browser here). The HTTP limits, the busy answer
and the Host check are tested without a browser in tests/serve.rs. The server binary is
$LAYERTRACE_BIN, else target/release/layertrace. Without Chromium the test is skipped
with a notice, except under CI=true, where it fails.
"""

import os
import shutil
import subprocess
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "glyph_g_liberationserif_cap120.png"


def chromium_path():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        found = shutil.which(name)
        if found:
            return found
    if os.environ.get("CI") == "true":
        pytest.fail("CI=true but no chromium on PATH: the browser test must run under CI")
    pytest.skip("no chromium on PATH: browser test skipped (apt-get install chromium)")


def binary():
    path = Path(os.environ.get("LAYERTRACE_BIN", ROOT / "target" / "release" / "layertrace"))
    if not path.exists():
        pytest.fail(f"{path} missing: build it first (cargo build --release)")
    return path


def start_server(*extra):
    """Starts `layertrace serve --port 0 …` and returns (process, base URL)."""
    proc = subprocess.Popen(
        [str(binary()), "serve", "--port", "0", *extra],
        stderr=subprocess.PIPE,
        text=True,
    )
    line = proc.stderr.readline()
    if "serving http://" not in line:
        proc.kill()
        pytest.fail(f"the server did not start: {line!r}")
    url = line.split("serving ", 1)[1].split()[0]
    assert url.startswith("http://127.0.0.1:"), url  # loopback by default
    return proc, url


@pytest.fixture
def server():
    proc, url = start_server()
    yield url
    proc.kill()
    proc.wait()


@pytest.fixture
def browser():
    from playwright.sync_api import sync_playwright

    path = chromium_path()
    with sync_playwright() as p:
        b = p.chromium.launch(
            executable_path=path,
            headless=True,
            args=["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-quic", "--no-first-run", "--disable-component-update",
                  "--disable-sync"],
        )
        yield b
        b.close()


def test_page_converts_a_sample_exactly(server, browser, tmp_path):
    page = browser.new_page(viewport={"width": 1500, "height": 1000})
    requests = []
    page.on("request", lambda r: requests.append(r.url))

    start = time.perf_counter()
    page.goto(server)
    page.wait_for_selector("body[data-state=ready]")
    load_ms = (time.perf_counter() - start) * 1000

    start = time.perf_counter()
    page.set_input_files("#file", str(SAMPLE))
    page.wait_for_selector("body[data-state=done]", timeout=60_000)
    convert_ms = (time.perf_counter() - start) * 1000

    assert page.inner_text("#differing") == "0"
    assert int(page.inner_text("#pieces")) > 0
    assert page.is_visible("#result")
    assert not page.is_visible("#error")
    # The SVG is shown: an image loaded from the answer, drawn at its size.
    page.wait_for_function("document.getElementById('out-svg').complete")
    svg_width = page.evaluate("document.getElementById('out-svg').naturalWidth")
    assert svg_width == 110, svg_width
    svg_text = page.evaluate(
        "fetch(document.getElementById('out-svg').src).then(r => r.text())"
    )
    assert svg_text.startswith("<svg") and "<path" in svg_text
    for picture in ("out-diff", "out-dec", "in-img"):
        page.wait_for_function(f"document.getElementById('{picture}').complete")
        assert page.evaluate(f"document.getElementById('{picture}').naturalWidth") > 0, picture
    # Downloads are offered under the input's name.
    assert page.get_attribute("#dl-svg", "download") == "glyph_g_liberationserif_cap120.svg"
    json_text = page.evaluate("fetch(document.getElementById('dl-json').href).then(r => r.text())")
    assert '"format": "layertrace-decomposition/2"' in json_text
    # Zoom changes the size the pictures are drawn at.
    page.fill("#zoom", "4")
    page.dispatch_event("#zoom", "input")
    assert page.evaluate("document.getElementById('out-diff').style.width") == "440px"
    # Nothing but the server itself was asked for.
    assert requests and all(u.startswith(server) or u.startswith("blob:") for u in requests), requests

    shot = Path(os.environ.get("LAYERTRACE_SCREENSHOT", tmp_path / "page.png"))
    page.fill("#zoom", "2")
    page.dispatch_event("#zoom", "input")
    page.screenshot(path=str(shot), full_page=True)
    print(f"\npage load {load_ms:.0f} ms, conversion through the page {convert_ms:.0f} ms, "
          f"screenshot {shot}")

    # A file that is not an image: the error is on the page.
    bad = tmp_path / "notes.png"
    bad.write_text("this is not an image\n")
    page.evaluate("document.body.dataset.state = 'ready'")
    page.set_input_files("#file", str(bad))
    page.wait_for_selector("#error:not([hidden])", timeout=30_000)
    message = page.inner_text("#error")
    assert "cannot decode notes.png" in message, message
    assert not page.is_visible("#result")



def test_page_colours_smooth_and_drag_and_drop(server, browser, tmp_path):
    """A colour logo dropped on the page (a real drop event with a DataTransfer), in four
    colours: exact, no seams, one swatch per colour; then smooth with ν = 1."""
    import base64

    logo = ROOT / "samples" / "colour" / "colour_logo_aa.png"
    page = browser.new_page(viewport={"width": 1500, "height": 1000})
    page.goto(server)
    page.wait_for_selector("body[data-state=ready]")
    page.fill("#colors", "4")
    page.dispatch_event("#colors", "input")
    assert page.is_disabled("#threshold") and page.is_disabled("#turdsize")

    data = base64.b64encode(logo.read_bytes()).decode()
    transfer = page.evaluate_handle(
        """(data) => {
            const bytes = Uint8Array.from(atob(data), (c) => c.charCodeAt(0));
            const t = new DataTransfer();
            t.items.add(new File([bytes], "logo.png", { type: "image/png" }));
            return t;
        }""",
        data,
    )
    page.dispatch_event("#drop", "drop", {"dataTransfer": transfer})
    page.wait_for_selector("body[data-state=done]", timeout=60_000)
    assert not page.is_visible("#error")
    assert page.inner_text("#differing") == "0"
    assert page.inner_text("#seams") == "0"
    swatches = page.eval_on_selector_all("#colours li", "items => items.map(i => i.textContent)")
    assert 2 <= len(swatches) <= 4 and all(s.endswith(" 0 differing") for s in swatches), swatches
    svg_text = page.evaluate("fetch(document.getElementById('out-svg').src).then(r => r.text())")
    assert svg_text.count("<path") == len(swatches)
    assert page.is_visible("#no-dec")
    assert page.get_attribute("#dl-svg", "download") == "logo.svg"

    page.fill("#smooth", "1")
    page.evaluate("document.body.dataset.state = 'ready'")
    page.click("#go")
    page.wait_for_selector("body[data-state=done]", timeout=60_000)
    assert page.inner_text("#seams") == "0"
    assert page.inner_text("#beyond").startswith("0 (ν = 1"), page.inner_text("#beyond")
    shot = os.environ.get("LAYERTRACE_SCREENSHOT")
    shot = Path(shot).with_name(Path(shot).stem + "-colour.png") if shot else tmp_path / "c.png"
    page.fill("#zoom", "3")
    page.dispatch_event("#zoom", "input")
    page.screenshot(path=str(shot), full_page=True)
    print(f"\ncolour screenshot {shot}")
