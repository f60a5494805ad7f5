#!/usr/bin/env python3
"""`feint collect` behind a real TLS reverse proxy: Debian's nginx with docs/nginx-feint.conf.

Makes a self-signed certificate (openssl) in a temporary folder, runs nginx as the current user
with its own configuration there (no system service; pid, logs and temp files in that folder),
in front of `feint collect --trusted-proxy 127.0.0.3` on loopback, and has headless Chromium
(--ignore-certificate-errors) play a whole session through https: consent, practice and rounds
with the arrow keys, the questionnaire, and the completion redirect. It then checks that the
events log has the browser's address from X-Forwarded-For (127.0.0.1; nginx itself connects
from 127.0.0.3), that every round was saved, and that `feint analyze` reads the folder.

Usage: collect_proxy.py FEINT_EXE DOCS_DIR
Exit 77 (skipped) when nginx, openssl, chromium or chromedriver is missing.
All traffic stays on 127.0.0.0/8.
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

from webdriver import WebDriver, free_port

SKIP = 77
ARROW = {"right": "\ue014", "left": "\ue012"}


def skip(why):
    print(f"SKIPPED: {why}")
    sys.exit(SKIP)


def nginx_config(docs_conf, work, port, upstream):
    """The shipped server block with only the machine-specific lines changed, in a minimal
    nginx.conf whose every path is in `work`."""
    block = open(docs_conf).read()
    subs = [
        (r"listen 443 ssl;", f"listen 127.0.0.1:{port} ssl;"),
        (r"ssl_certificate     \S+;", f"ssl_certificate     {work}/cert.pem;"),
        (r"ssl_certificate_key \S+;", f"ssl_certificate_key {work}/key.pem;"),
        (r"proxy_pass http://127\.0\.0\.1:8080;",
         f"proxy_pass http://127.0.0.1:{upstream};\n        proxy_bind 127.0.0.3;"),
    ]
    for pattern, repl in subs:
        block, n = re.subn(pattern, repl, block)
        if n != 1:
            raise RuntimeError(f"docs/nginx-feint.conf: expected one '{pattern}'")
    temp = "\n".join(f"    {k}_temp_path {work}/{k};" for k in
                     ["client_body", "proxy", "fastcgi", "uwsgi", "scgi"])
    return f"""daemon off;
master_process off;
worker_processes 1;
pid {work}/nginx.pid;
error_log {work}/error.log info;
events {{ worker_connections 128; }}
http {{
    access_log {work}/access.log;
{temp}
    default_type application/octet-stream;
{block}
}}
"""


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 64
    feint, docs = sys.argv[1], sys.argv[2]
    nginx = shutil.which("nginx") or ("/usr/sbin/nginx" if os.path.exists("/usr/sbin/nginx") else None)
    openssl = shutil.which("openssl")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_exe = shutil.which("chromedriver")
    if not nginx or not openssl:
        skip("nginx and openssl are needed (Debian: apt-get install nginx openssl)")
    if not chromium or not driver_exe:
        skip("chromium and chromedriver are needed (Debian: apt-get install chromium chromium-driver)")

    work = tempfile.mkdtemp(prefix="feint-collect-proxy-")
    study = os.path.join(work, "study")
    os.makedirs(study)
    procs = []
    wd = None
    failures = []

    def check(cond, what):
        if not cond:
            failures.append(what)

    try:
        r = subprocess.run([openssl, "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "2",
                            "-subj", "/CN=127.0.0.1", "-keyout", f"{work}/key.pem",
                            "-out", f"{work}/cert.pem"], capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"openssl: {r.stderr}")
        tls = free_port()
        completion = f"https://127.0.0.1:{tls}/admin?token=tok&cc=C0DE"
        with open(os.path.join(study, "feint.toml"), "w") as f:
            f.write(f'[collect]\nrobot-speed = 6\niterations = 4\npractice = 1\n'
                    f'completion-url = "{completion}"\nconsent = "You may stop at any time."\n')
        srv = subprocess.Popen([feint, "collect", study, "--port", "0", "--admin-token", "tok",
                                "--trusted-proxy", "127.0.0.3"],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        procs.append(srv)
        port = None
        for line in srv.stdout:
            if line.startswith("port: "):
                port = int(line.split()[1])
                break
        if not port:
            raise RuntimeError("feint collect did not start")
        with open(os.path.join(work, "nginx.conf"), "w") as f:
            f.write(nginx_config(os.path.join(docs, "nginx-feint.conf"), work, tls, port))
        ngx = subprocess.Popen([nginx, "-p", work, "-c", f"{work}/nginx.conf", "-e", f"{work}/error.log"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        procs.append(ngx)
        for _ in range(100):
            try:
                import socket
                socket.create_connection(("127.0.0.1", tls), timeout=0.2).close()
                break
            except OSError:
                if ngx.poll() is not None:
                    raise RuntimeError("nginx did not start: " + open(f"{work}/error.log").read())
                time.sleep(0.05)
        dport = free_port()
        drv = subprocess.Popen([driver_exe, f"--port={dport}"], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
        procs.append(drv)
        wd = WebDriver(dport)
        wd.wait_ready()
        wd.new_session({"browserName": "chrome", "acceptInsecureCerts": True, "goog:chromeOptions": {
            "binary": chromium,
            "args": ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                     "--ignore-certificate-errors", "--no-proxy-server",
                     "--disable-background-networking", "--disable-component-update", "--disable-sync",
                     "--disable-dev-shm-usage", f"--user-data-dir={work}/profile", "--window-size=1000,1000"]}})
        base = f"https://127.0.0.1:{tls}"
        wd.s("POST", "/url", {"url": base + "/?participant=PX1"})
        wd.wait("return document.body.dataset.state === 'consent'", what="consent (through https)")
        check(wd.js("return location.protocol") == "https:", "the page came through https")
        wd.click("#agree")
        n = 0
        while True:
            state = wd.wait("var s = document.body.dataset.state, r = document.body.dataset.round;"
                            "return (s === 'game' && r === 'ready' && !document.getElementById('start').disabled)"
                            " || s === 'questionnaire' ? s : null", what="a round or the questionnaire")
            if state == "questionnaire":
                break
            n += 1
            direction = "right" if n % 2 else "left"
            wd.click("#start")
            wd.wait("return document.body.dataset.round === 'running'", what="round running")
            wd.keys([{"type": "keyDown", "value": ARROW[direction]}, {"type": "pause", "duration": 200},
                     {"type": "keyUp", "value": ARROW[direction]}])
            wd.wait("return document.body.dataset.round !== 'running'", what="round end")
            if n > 10:
                raise RuntimeError("more rounds than the study has")
        for item, v in [("entertainment", 6), ("deception", 5), ("intelligence", 7), ("trust", 2)]:
            wd.click(f"#{item}-{v}")
        wd.click("#intentional-yes")
        wd.click("#qsubmit")
        wd.wait("return document.body.dataset.state === 'done'", what="completion page")
        # The page redirects to the completion URL after 3 s (here: the admin page, through nginx).
        href = wd.wait("return location.href.indexOf('cc=C0DE') >= 0 ? location.href : null",
                       timeout=15, what="the completion redirect")
        check(href == completion, f"completion redirect to {completion}, got {href}")
        check("PX1" in wd.js("return document.body.textContent"),
              "the completion URL (the admin page) was served through the proxy")
    finally:
        if wd:
            wd.quit()
        for p in reversed(procs):
            p.send_signal(signal.SIGTERM)
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()

    events = open(os.path.join(study, "collect", "events.csv")).read()
    check(",PX1,joined,from 127.0.0.1" in events,
          "the events log has the browser's address from X-Forwarded-For")
    check("from 127.0.0.3" not in events, "the proxy's own address (127.0.0.3) is not taken for the client's")
    logs = open(os.path.join(study, "logs", "PX1.csv")).read().splitlines()
    its = sorted({line.split(",")[2] for line in logs[1:]})
    check(its == ["1", "2", "3", "4"], f"4 rounds saved through the proxy, got {its}")
    check(n == 5, f"5 rounds played (1 practice + 4), got {n}")
    access = open(os.path.join(work, "access.log")).read()
    check("POST /api/round/submit" in access, "the rounds went through nginx")
    r = subprocess.run([feint, "analyze", study, "-o", os.path.join(work, "out")], capture_output=True, text=True)
    check(r.returncode == 0, f"feint analyze: {r.stderr}")
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        print(f"(folder kept: {work})")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("OK: a whole session through nginx + TLS; X-Forwarded-For in the events log; completion redirect")
    return 0


if __name__ == "__main__":
    sys.exit(main())
