#!/usr/bin/env python3
"""The study report in a real browser.

Runs `feint analyze STUDY -o WORK/out`, then opens WORK/out/report.html from disk in Debian's
headless Chromium (driven by chromedriver over WebDriver, on 127.0.0.1 only) with the network
disabled, and checks that the page
  - makes no request other than for the file itself (performance log: Network.requestWillBeSent),
  - logs no console error or warning (browser log),
  - shows every figure as inline SVG with a size and alt text (its <title>; <img> alt),
  - at 1280 px and at a phone's 390 px has no horizontal overflow: no element reaches past the
    right edge unless it lies inside a box of its own that scrolls (wide tables do),
  - names no absolute path (text, links), so the folder can be moved or sent,
  - prints a settings block (feint.toml) that `feint analyze --config` accepts,
  - prints on A4 (WebDriver print).
Optionally saves screenshots at 1280 and 390 px (--screenshot-dir: report-1280.png,
report-390.png) and the A4 print (--print-pdf).

Python 3 standard library only. Exits 77 (ctest SKIP_RETURN_CODE) with a message when chromium,
chromedriver or the feint binary is missing.
"""
import argparse
import base64
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

from webdriver import WebDriver, find, free_port

SKIP = 77


# Elements whose right edge passes the window's, unless an ancestor that scrolls horizontally
# (overflow-x auto/scroll) and itself fits the window contains them (a wide table in its box).
OVERFLOW_JS = """
const W = document.documentElement.clientWidth;
const out = [];
for (const el of document.body.querySelectorAll('*')) {
  if (el.closest('svg') && el.tagName.toLowerCase() !== 'svg') continue;
  const r = el.getBoundingClientRect();
  if (r.width === 0 || r.right <= W + 0.5) continue;
  let boxed = false;
  for (let a = el.parentElement; a; a = a.parentElement) {
    const ox = getComputedStyle(a).overflowX;
    if ((ox === 'auto' || ox === 'scroll') && a.getBoundingClientRect().right <= W + 0.5) {
      boxed = true;
      break;
    }
  }
  if (!boxed) {
    out.push(el.tagName.toLowerCase() + (el.id ? '#' + el.id : '') +
             (el.className && typeof el.className === 'string' ? '.' + el.className : '') +
             ' (right edge ' + Math.round(r.right) + ' px, window ' + W + ' px)');
  }
  if (out.length >= 10) break;
}
return out;
"""

# The smallest text of each figure as drawn (px): the drawing's smallest font (data-min-font-pt, in
# the SVG's viewBox units, pt) times the drawing's scale. Hidden drawings (the one-column drawing
# at 1280 px, the two-column one on a phone) are not seen and not counted.
FONT_JS = """
const out = [];
for (const fig of document.querySelectorAll('figure')) {
  for (const s of fig.querySelectorAll('svg')) {
    if (s.getClientRects().length === 0) continue;
    const vb = s.viewBox && s.viewBox.baseVal;
    if (!vb || !vb.width) continue;
    // 7 pt: the plot module's tick labels (plot::kTickFontSize), when the page does not say.
    const holder = s.closest('[data-min-font-pt]');
    const pt = parseFloat(holder ? holder.getAttribute('data-min-font-pt') : '7');
    out.push([fig.id, pt * s.getBoundingClientRect().width / vb.width]);
  }
}
return out;
"""

# Figures (inline SVG) need a non-empty <title> (their accessible name); images need alt.
ALT_JS = """
let missing = 0;
for (const s of document.querySelectorAll('figure svg')) {
  const t = s.querySelector('title');
  if (s.getAttribute('role') !== 'img' || !t || !t.textContent.trim()) missing++;
}
for (const i of document.querySelectorAll('img')) {
  if (!(i.getAttribute('alt') || '').trim()) missing++;
}
return missing;
"""

ABSOLUTE = re.compile(r'(?:href|src)="(?:/|file:)|(?<![\w.~-])/(?:home|tmp|work|usr|root|var|mnt|srv|opt|Users)/')


def absolute_paths(html, roots):
    """Absolute paths in the page: the run's own folders, links to / or file:, /home/... text."""
    found = [f"names the absolute path {r}" for r in roots
             if re.search(r"(?<![\w./-])" + re.escape(r), html)]
    text = re.sub(r"<svg.*?</svg>", "", html, flags=re.S)
    for m in ABSOLUTE.finditer(text):
        found.append(f"names an absolute path: ...{text[max(0, m.start() - 40):m.end() + 40]}...")
    return found[:10]


def settings_refused(feint, study, html, work):
    """The settings block (pre.settings) must be a feint.toml that feint analyze accepts."""
    m = re.search(r'<pre class="settings">(.*?)</pre>', html, re.S)
    if not m:
        return ["no settings block (pre.settings) in the report"]
    import html as htmllib
    toml = os.path.join(work, "printed-settings.toml")
    with open(toml, "w", encoding="utf-8") as f:
        f.write(htmllib.unescape(m.group(1)))
    out2 = os.path.join(work, "out-from-printed-settings")
    shutil.rmtree(out2, ignore_errors=True)
    r = subprocess.run([feint, "analyze", study, "--config", toml, "-o", out2, "--no-figures",
                        "--no-report"], capture_output=True, text=True)
    if r.returncode != 0:
        return [f"feint refuses the report's settings block ({r.returncode}): {r.stderr.strip()}"]
    return []


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--feint", required=True)
    ap.add_argument("--study", required=True)
    ap.add_argument("--work", default=None)
    ap.add_argument("--screenshot", default=None, help="save a PNG at 1280 px width here")
    ap.add_argument("--height", type=int, default=0, help="screenshot height (0 = whole page)")
    ap.add_argument("--scroll", type=int, default=0,
                    help="screenshot from this page offset (px; needs --height)")
    ap.add_argument("--print-pdf", default=None, help="save the A4 print here")
    ap.add_argument("--screenshot-dir", default=None,
                    help="save report-1280.png and report-390.png (top of the page) here")
    args = ap.parse_args()

    chromium = find(["chromium", "chromium-browser", "google-chrome"])
    driver_bin = find(["chromedriver"])
    if not chromium or not driver_bin:
        print("chromium or chromedriver not installed (Debian: chromium chromium-driver): "
              "browser check skipped")
        return SKIP
    if not os.access(args.feint, os.X_OK):
        print(f"{args.feint}: feint binary not built: browser check skipped")
        return SKIP

    work = args.work or tempfile.mkdtemp(prefix="feint-browser-")
    if args.screenshot_dir:
        os.makedirs(args.screenshot_dir, exist_ok=True)
    out = os.path.join(work, "out")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(work, exist_ok=True)
    r = subprocess.run([args.feint, "analyze", args.study, "-o", out], capture_output=True,
                       text=True)
    if r.returncode != 0:
        print(f"feint analyze failed ({r.returncode}): {r.stderr}")
        return 1
    report = os.path.abspath(os.path.join(out, "report.html"))
    page_url = "file://" + report
    with open(report, encoding="utf-8") as f:
        html = f.read()
    expected_figures = html.count("<figure")
    failures = []
    failures += absolute_paths(html, [os.path.abspath(args.study), os.path.abspath(out),
                                      os.path.abspath(work)])
    failures += settings_refused(args.feint, args.study, html, work)

    port = free_port()
    profile = tempfile.mkdtemp(prefix="feint-chromium-")
    log = open(os.path.join(work, "chromedriver.log"), "w")
    proc = subprocess.Popen([driver_bin, f"--port={port}", "--allowed-ips=127.0.0.1"],
                            stdout=log, stderr=subprocess.STDOUT)
    d = WebDriver(port)
    try:
        d.wait_ready()
        caps = {
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": chromium,
                "args": [
                    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                    "--no-first-run", "--disable-background-networking",
                    "--disable-component-update", "--disable-sync",
                    "--disable-default-apps", "--disable-extensions",
                    "--disable-dev-shm-usage", "--hide-scrollbars",
                    f"--user-data-dir={profile}",
                    # No network: every host resolves to nothing and every proxy is refused.
                    "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9",
                    "--force-device-scale-factor=1", "--window-size=1280,1000",
                ],
            },
            "goog:loggingPrefs": {"browser": "ALL", "performance": "ALL"},
        }
        d.new_session(caps)
        d.s("POST", "/window/rect", {"width": 1280, "height": 1000})
        # Reading a log empties it: what the browser's own start page loaded is not counted.
        d.s("POST", "/url", {"url": "about:blank"})
        for kind in ("browser", "performance"):
            d.s("POST", "/se/log", {"type": kind})
        d.s("POST", "/url", {"url": page_url})

        js = d.js
        for _ in range(50):
            if js("return document.readyState") == "complete":
                break
            time.sleep(0.1)
        for width in (390, 1280):
            d.s("POST", "/window/rect", {"width": width, "height": 1000})
            time.sleep(0.2)
            inner = js("return window.innerWidth")
            scroll_width = js("return document.documentElement.scrollWidth")
            if scroll_width > inner:
                failures.append(f"horizontal scroll at {width} px: page {scroll_width} px wide, "
                                f"window {inner} px")
            for o in js(OVERFLOW_JS) or []:
                failures.append(f"at {width} px, {o} reaches past the right edge outside a "
                                f"scrolling box of its own")
            # Readable on a phone: every figure's smallest text drawn at 9 px or more.
            fonts = js(FONT_JS) or []
            if len(fonts) != expected_figures:
                failures.append(f"at {width} px, {len(fonts)} figure drawings shown, "
                                f"{expected_figures} expected")
            for fig_id, px in fonts:
                if px < 9:
                    failures.append(f"at {width} px, {fig_id}'s smallest text is drawn at "
                                    f"{px:.1f} px (< 9 px)")
            if width == 390:
                print(f"at 390 px the figures' smallest text is {min(p for _, p in fonts):.1f} px"
                      if fonts else "at 390 px no figure is shown")
            if args.screenshot_dir:
                js("window.scrollTo(0, 0); return 0")
                d.s("POST", "/window/rect", {"width": width, "height": 1400 if width > 500 else 1600})
                time.sleep(0.2)
                d.screenshot(os.path.join(args.screenshot_dir, f"report-{width}.png"))
                # A wide table in its own scrolling box, and the settings block.
                for anchor in ("table1", "settings"):
                    js(f"document.getElementById('{anchor}').scrollIntoView(); return 0")
                    time.sleep(0.1)
                    d.screenshot(os.path.join(args.screenshot_dir,
                                              f"report-{width}-{anchor}.png"))
                d.s("POST", "/window/rect", {"width": 1280, "height": 1000})
        inner = js("return window.innerWidth")
        scroll_width = js("return document.documentElement.scrollWidth")
        missing_alt = js(ALT_JS)
        if missing_alt:
            failures.append(f"{missing_alt} figure(s) or image(s) without alt text")
        sizes = js("return Array.from(document.querySelectorAll('figure svg'))"
                   ".filter(s => s.getClientRects().length > 0)"
                   ".map(s => [s.getBoundingClientRect().width, s.getBoundingClientRect().height])")
        if len(sizes) != expected_figures or expected_figures == 0:
            failures.append(f"{len(sizes)} inline SVG figures shown, {expected_figures} expected")
        for i, (w, h) in enumerate(sizes):
            if w < 300 or h < 100:
                failures.append(f"figure {i + 1} is drawn {w:.0f} x {h:.0f} px")
        external = js("return Array.from(document.querySelectorAll('[src],link[href],script'))"
                      ".length")
        if external:
            failures.append(f"{external} elements that load something (src, link, script)")

        height = js("return document.documentElement.scrollHeight")
        if args.screenshot:
            shot_h = args.height or height
            d.s("POST", "/window/rect", {"width": 1280, "height": shot_h})
            if args.scroll:
                js(f"window.scrollTo(0, {args.scroll}); return 0")
            d.screenshot(args.screenshot)
        pdf = base64.b64decode(d.s("POST", "/print", {
            "page": {"width": 21.0, "height": 29.7}, "background": True,
            "margin": {"top": 1, "bottom": 1, "left": 1, "right": 1}}))
        pages = pdf.count(b"/Type /Page") - pdf.count(b"/Type /Pages")
        if not pdf.startswith(b"%PDF") or pages < 1:
            failures.append("printing on A4 gave no PDF")
        if args.print_pdf:
            with open(args.print_pdf, "wb") as f:
                f.write(pdf)

        console = d.s("POST", "/se/log", {"type": "browser"}) or []
        for e in console:
            if e.get("level") in ("SEVERE", "WARNING"):
                failures.append(f"console {e.get('level')}: {e.get('message')}")
        perf = d.s("POST", "/se/log", {"type": "performance"}) or []
        requests = []
        for e in perf:
            msg = json.loads(e["message"])["message"]
            if msg.get("method") == "Network.requestWillBeSent":
                requests.append(msg["params"]["request"]["url"])
        if not requests:
            failures.append("the performance log saw no request at all (is it working?)")
        for url in requests:
            if url != page_url:
                failures.append(f"request made: {url}")
        print(f"report.html: {len(sizes)} figures, page {scroll_width} x {height} px at width "
              f"{inner}, {len(requests)} request(s) ({', '.join(requests)}), "
              f"{len(console)} console message(s), A4 print {len(pdf)} bytes")
    finally:
        d.quit()
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.close()
        shutil.rmtree(profile, ignore_errors=True)
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
