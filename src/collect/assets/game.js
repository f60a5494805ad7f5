// feint collect: the game page (the seed paper's Fig. 8). No external resources.
// The pad position is integrated from the key state and the elapsed time (performance.now()),
// and sampled on every animation frame, so a dropped frame never distorts it; each step is at most
// pad_speed * dt, which the server checks.
// A pointer study (st.belief === 'pointer', K targets on a map) has no pad: the participant holds
// the mouse button or a finger on the map where they believe the robot goes. The trial (t = 0)
// starts at their first touch, so every sample is a point they chose; the page samples the point
// held (the last one after a release) at the study's sample rate, in map metres.
'use strict';
(function () {
  const $ = (id) => document.getElementById(id);
  const params = new URLSearchParams(location.search);
  let pid = params.get('participant') || params.get('PROLIFIC_PID') || '';
  let st = null;        // participant status from the server
  let round = null;     // the round being played
  // read by the browser test; toClient maps a map point (m) to the viewport (pointer studies)
  const test = { intervals: [], lastTrace: null, toClient: null };
  window.__feint = test;

  // ---- talking to the server: retried until it answers (network errors, 5xx) ----
  async function call(path, body) {
    let wait = 250;
    for (;;) {
      try {
        const r = await fetch(path, { method: 'POST', body: body || '', cache: 'no-store',
                                      headers: { 'Content-Type': 'text/plain' } });
        const json = await r.json().catch(() => ({}));
        if (r.status < 500) { delete document.body.dataset.saveProblem; return { status: r.status, json }; }
        // 503: the server could not write (disk full...); nothing was saved, so wait and retry.
        $('status').textContent = r.status === 503 ? 'Could not save, please wait…'
                                                   : 'Connection problem: retrying…';
      } catch (e) { $('status').textContent = 'Connection problem: retrying…'; }
      document.body.dataset.saveProblem = '1';
      await new Promise((res) => setTimeout(res, wait));
      wait = Math.min(wait * 2, 4000);
    }
  }
  const q = (extra) => '?participant=' + encodeURIComponent(pid) + (extra || '');

  function show(id) {
    for (const s of ['consent', 'game', 'questionnaire', 'done', 'error']) $(s).hidden = s !== id;
    document.body.dataset.state = id;
  }
  function fail(text) { $('error-text').textContent = text; show('error'); }

  function progressText() {
    if (st.practice_saved < st.practice) return `Practice round ${st.practice_saved + 1} of ${st.practice}`;
    if (st.rounds_saved < st.iterations) return `Round ${st.rounds_saved + 1} of ${st.iterations}`;
    return 'Questionnaire';
  }

  function enter(status) {
    st = status;
    $('progress').textContent = progressText();
    if (st.stage === 'consent') {
      $('consent-text').textContent = st.consent;
      show('consent');
    } else if (st.stage === 'rounds') {
      show('game');
      ready();
    } else if (st.stage === 'questionnaire') {
      buildQuestionnaire();
      show('questionnaire');
    } else {
      finish();
    }
  }

  async function join() {
    const path = '/api/join' + (pid ? q() : '');
    const r = await call(path);
    if (r.status !== 200) return fail(r.json.message || 'The study cannot be joined.');
    pid = r.json.participant;
    if (params.get('participant') !== pid) {  // so that a reload resumes this participant
      params.set('participant', pid);
      history.replaceState(null, '', location.pathname + '?' + params.toString());
    }
    enter(r.json);
  }

  // ---- the field ----
  const canvas = $('field');
  const ctx = canvas.getContext('2d');
  let pad = 0.5, robot = { x: 0, y: 0 };
  function scale() {
    const dpr = window.devicePixelRatio || 1;
    let w = canvas.clientWidth || 800, h = Math.round(w * 0.6);
    if (pointerStudy()) {  // the map keeps its proportions and fits the window's height
      const m = st.map, aspect = (m.y_max - m.y_min) / (m.x_max - m.x_min);
      const maxH = Math.max(260, window.innerHeight * 0.62);
      canvas.style.width = w * aspect > maxH && !canvas.style.width ? Math.floor(maxH / aspect) + 'px' : canvas.style.width;
      w = canvas.clientWidth || w;
      h = Math.round(w * aspect);
    }
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr);
      canvas.height = Math.round(h * dpr);
    }
    return dpr;
  }
  function pointerStudy() { return !!(st && st.belief === 'pointer'); }
  function draw() {
    if (pointerStudy()) return drawMap();
    const dpr = scale();
    const W = canvas.width / dpr, H = canvas.height / dpr;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, W, H);
    const d = st.target_distance, h = st.target_height;
    const top = 110, bottom = H - 40;  // y of the targets' row and of the start
    const s = Math.min((bottom - top) / h, (W - 160) / d);
    const cx = W / 2;
    const X = (x) => cx + x * s, Y = (y) => bottom - y * s;
    const xl = X(-d / 2), xr = X(d / 2);
    // pad track across the top; pad 0 is above the left target, 1 above the right one
    ctx.strokeStyle = '#c3cad6'; ctx.lineWidth = 6; ctx.lineCap = 'round';
    ctx.beginPath(); ctx.moveTo(xl, 34); ctx.lineTo(xr, 34); ctx.stroke();
    ctx.fillStyle = '#5b6475'; ctx.font = '13px system-ui, sans-serif'; ctx.textAlign = 'center';
    ctx.fillText('pad', cx, 18);
    const px = xl + pad * (xr - xl);
    ctx.fillStyle = '#1f6feb';
    ctx.fillRect(px - 40, 24, 80, 20);
    // targets
    for (const [x, colour, name] of [[xl, '#d9480f', 'left'], [xr, '#2b8a3e', 'right']]) {
      ctx.fillStyle = colour;
      ctx.beginPath(); ctx.arc(x, Y(h), 22, 0, 2 * Math.PI); ctx.fill();
      ctx.fillStyle = '#fff'; ctx.font = 'bold 13px system-ui, sans-serif';
      ctx.fillText(name, x, Y(h) + 4);
    }
    // start mark and robot
    ctx.strokeStyle = '#d5dae3'; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.arc(X(0), Y(0), 18, 0, 2 * Math.PI); ctx.stroke();
    ctx.fillStyle = '#4a5261';
    ctx.beginPath(); ctx.arc(X(robot.x), Y(robot.y), 14, 0, 2 * Math.PI); ctx.fill();
    ctx.fillStyle = '#fff';
    ctx.beginPath(); ctx.arc(X(robot.x), Y(robot.y) - 5, 4, 0, 2 * Math.PI); ctx.fill();
  }

  // ---- the map of a pointer study: start, K targets, robot, the belief point ----
  const COLOURS = ['#d9480f', '#2b8a3e', '#7048e8', '#c2255c', '#1098ad', '#e67700', '#5c940d', '#364fc7'];
  let belief = null, holding = false, view = null;  // belief: {x, y} in metres; view: map -> px
  function mapView() {
    const dpr = scale();
    const W = canvas.width / dpr, H = canvas.height / dpr, m = st.map;
    const s = Math.min(W / (m.x_max - m.x_min), H / (m.y_max - m.y_min));
    return { dpr, W, H, s, X: (x) => (x - m.x_min) * s, Y: (y) => (m.y_max - y) * s };
  }
  function drawMap() {
    view = mapView();
    const { dpr, W, H, s, X, Y } = view;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, W, H);
    ctx.strokeStyle = '#eef1f6'; ctx.lineWidth = 1;  // a 1 m grid, so that distances read
    for (let x = Math.ceil(st.map.x_min); x <= st.map.x_max; x++) { ctx.beginPath(); ctx.moveTo(X(x), 0); ctx.lineTo(X(x), H); ctx.stroke(); }
    for (let y = Math.ceil(st.map.y_min); y <= st.map.y_max; y++) { ctx.beginPath(); ctx.moveTo(0, Y(y)); ctx.lineTo(W, Y(y)); ctx.stroke(); }
    const r = Math.max(15, Math.min(26, 0.32 * s));  // targets large enough to see on a phone
    if (round && round.layout) {
      ctx.textAlign = 'center'; ctx.textBaseline = 'middle';
      round.layout.forEach(([x, y], k) => {
        ctx.fillStyle = COLOURS[k % COLOURS.length];
        ctx.beginPath(); ctx.arc(X(x), Y(y), r, 0, 2 * Math.PI); ctx.fill();
        ctx.fillStyle = '#fff'; ctx.font = `bold ${Math.round(r * 0.9)}px system-ui, sans-serif`;
        ctx.fillText(String.fromCharCode(65 + k), X(x), Y(y) + 1);
      });
      ctx.strokeStyle = '#c3cad6'; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(X(round.start[0]), Y(round.start[1]), 18, 0, 2 * Math.PI); ctx.stroke();
    }
    if (belief) {  // the participant's point: filled while held, a ring once released
      const bx = X(belief.x), by = Y(belief.y);
      ctx.strokeStyle = '#1f6feb'; ctx.fillStyle = 'rgba(31,111,235,0.28)'; ctx.lineWidth = 3;
      ctx.beginPath(); ctx.arc(bx, by, 12, 0, 2 * Math.PI); if (holding) ctx.fill(); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(bx - 18, by); ctx.lineTo(bx + 18, by); ctx.moveTo(bx, by - 18); ctx.lineTo(bx, by + 18); ctx.stroke();
    }
    ctx.fillStyle = '#4a5261';
    ctx.beginPath(); ctx.arc(X(robot.x), Y(robot.y), 14, 0, 2 * Math.PI); ctx.fill();
    ctx.fillStyle = '#fff';
    ctx.beginPath(); ctx.arc(X(robot.x), Y(robot.y) - 5, 4, 0, 2 * Math.PI); ctx.fill();
    if (document.body.dataset.round === 'waiting') {
      ctx.fillStyle = '#1d2330'; ctx.font = `${W < 500 ? 14 : 16}px system-ui, sans-serif`; ctx.textAlign = 'center';
      ctx.fillText('Touch and hold where the robot is going', W / 2, 22);
      ctx.fillText('(it starts when you touch)', W / 2, 42);
    }
  }
  let changes = [];  // [performance.now(), x, y] each time the held point moved, in order
  function pointAt(e) {  // the map point under the pointer, kept inside the map
    const rect = canvas.getBoundingClientRect(), m = st.map;
    const x = m.x_min + (e.clientX - rect.left) / view.s;
    const y = m.y_max - (e.clientY - rect.top) / view.s;
    return { x: Math.min(m.x_max, Math.max(m.x_min, x)), y: Math.min(m.y_max, Math.max(m.y_min, y)) };
  }
  test.held = () => holding;
  test.toClient = (x, y) => {
    const rect = canvas.getBoundingClientRect(), m = st.map;
    return [rect.left + (x - m.x_min) * view.s, rect.top + (m.y_max - y) * view.s];
  };
  function hold(e) {
    belief = pointAt(e);
    const now = performance.now();
    if (document.body.dataset.round === 'waiting') beginTrial(now);
    if (running) changes.push([now, belief.x, belief.y]);
    draw();
  }
  canvas.addEventListener('pointerdown', (e) => {
    if (!pointerStudy() || !round || !['waiting', 'running'].includes(document.body.dataset.round)) return;
    e.preventDefault();
    canvas.setPointerCapture(e.pointerId);
    holding = true;
    hold(e);
  });
  canvas.addEventListener('pointermove', (e) => { if (holding && running) { e.preventDefault(); hold(e); } });
  for (const ev of ['pointerup', 'pointercancel', 'lostpointercapture'])
    canvas.addEventListener(ev, () => { if (holding) { holding = false; if (pointerStudy()) draw(); } });

  // ---- keys and pad ----
  const held = { left: false, right: false };
  let lastNow = 0, endNow = 0, running = false;
  function advance(now) {  // integrate the pad from lastNow to now at the held direction
    if (!running) return;
    now = Math.min(Math.max(now, lastNow), endNow);
    const dir = (held.right ? 1 : 0) - (held.left ? 1 : 0);
    if (dir !== 0) pad = Math.min(1, Math.max(0, pad + dir * st.pad_speed * (now - lastNow) / 1000));
    lastNow = now;
  }
  let keyLog = [];  // [t, key, down] during the round (read by the browser test)
  function setKey(which, down) {
    if (held[which] === down) return;
    const now = performance.now();
    advance(now);
    if (running) keyLog.push([(Math.min(Math.max(now, lastNow), endNow) - startNow) / 1000, which, down]);
    held[which] = down;
    $(which).classList.toggle('held', down);
  }
  window.addEventListener('keydown', (e) => {
    if (e.key === 'ArrowLeft' || e.key === 'ArrowRight') {
      e.preventDefault();
      setKey(e.key === 'ArrowLeft' ? 'left' : 'right', true);
    }
  });
  window.addEventListener('keyup', (e) => {
    if (e.key === 'ArrowLeft' || e.key === 'ArrowRight') {
      e.preventDefault();
      setKey(e.key === 'ArrowLeft' ? 'left' : 'right', false);
    }
  });
  window.addEventListener('blur', () => { setKey('left', false); setKey('right', false); });
  for (const which of ['left', 'right']) {
    const b = $(which);
    b.addEventListener('pointerdown', (e) => { e.preventDefault(); b.setPointerCapture(e.pointerId); setKey(which, true); });
    for (const ev of ['pointerup', 'pointercancel', 'lostpointercapture']) b.addEventListener(ev, () => setKey(which, false));
  }

  // ---- a round ----
  function ready() {
    running = false;
    pad = 0.5; robot = { x: 0, y: 0 };
    if (pointerStudy()) {
      round = null; belief = null; holding = false;
      $('left').hidden = true; $('right').hidden = true;
      $('instructions').textContent = 'Press \u201cWatch the robot\u201d, then hold the mouse button or your finger on the map ' +
        'where you think the robot (grey) is going; the robot starts when you first touch. Move it whenever ' +
        'you change your mind. When you let go, your last point counts.';
    }
    draw();
    $('start').disabled = false;
    $('start').textContent = 'Start';
    $('status').textContent = st.practice_saved < st.practice ? 'Practice: this round is not counted.' : '';
    document.body.dataset.round = 'ready';
  }
  function robotAt(te) {
    const t = round.t;
    if (te >= round.duration) return { x: round.x[t.length - 1], y: round.y[t.length - 1] };
    let lo = 0, hi = t.length - 1;
    while (hi - lo > 1) { const m = (lo + hi) >> 1; if (t[m] <= te) lo = m; else hi = m; }
    const f = (te - t[lo]) / (t[hi] - t[lo]);
    return { x: round.x[lo] + f * (round.x[hi] - round.x[lo]), y: round.y[lo] + f * (round.y[hi] - round.y[lo]) };
  }
  let samples = [], startNow = 0, lastFrame = 0;
  function frame() {
    const now = performance.now();
    if (lastFrame) test.intervals.push(now - lastFrame);
    lastFrame = now;
    if (now >= endNow) {
      advance(endNow);
      samples.push([round.duration, pad]);  // the last sample is exactly the end of the round
      robot = robotAt(round.duration);
      draw();
      running = false;
      save();
      return;
    }
    advance(now);
    const te = (now - startNow) / 1000;
    if (te > samples[samples.length - 1][0] && te < round.duration) samples.push([te, pad]);
    robot = robotAt(te);
    draw();
    requestAnimationFrame(frame);
  }
  $('start').addEventListener('click', async () => {
    $('start').disabled = true;
    $('status').textContent = '';
    const r = await call('/api/round/start' + q());
    if (r.status !== 200) return fail(r.json.message || 'The round cannot start.');
    round = r.json;
    if (pointerStudy()) {  // the map is shown; the trial waits for the first touch
      robot = { x: round.start[0], y: round.start[1] };
      document.body.dataset.round = 'waiting';
      $('start').textContent = 'Touch the map';
      draw();
      return;
    }
    pad = 0.5;
    samples = [[0, 0.5]];
    startNow = performance.now();
    lastNow = startNow;
    endNow = startNow + round.duration * 1000;
    lastFrame = 0;
    keyLog = [[0, 'left', held.left], [0, 'right', held.right]];
    running = true;
    document.body.dataset.round = 'running';
    $('start').textContent = 'Watch the robot';
    requestAnimationFrame(frame);
  });
  // A pointer trial: t = 0 at the first touch; samples at k / sample_rate, each the point held at
  // that time (from the recorded changes, so a late frame costs nothing); the last at the end.
  let nextK = 0, ci = 0;
  function beginTrial(now) {
    startNow = now; endNow = now + round.duration * 1000;
    samples = []; changes = []; nextK = 0; ci = 0; lastFrame = 0;
    running = true;
    document.body.dataset.round = 'running';
    $('start').textContent = 'Watch the robot';
    requestAnimationFrame(framePointer);
  }
  function heldAt(when) {
    while (ci + 1 < changes.length && changes[ci + 1][0] <= when) ci++;
    return changes[ci];
  }
  function framePointer() {
    const now = performance.now();
    if (lastFrame) test.intervals.push(now - lastFrame);
    lastFrame = now;
    const te = Math.min((now - startNow) / 1000, round.duration);
    for (;;) {
      const t = nextK / st.sample_rate;
      if (t > te || t >= round.duration) break;
      const c = heldAt(startNow + t * 1000);
      samples.push([t, c[1], c[2]]);
      nextK++;
    }
    robot = robotAt(te);
    if (now >= endNow) {
      const c = heldAt(endNow);
      samples.push([round.duration, c[1], c[2]]);  // the last sample is exactly the end
      running = false;
      draw();
      save();
      return;
    }
    draw();
    requestAnimationFrame(framePointer);
  }
  async function save() {
    document.body.dataset.round = 'saving';
    $('status').textContent = 'Saving…';
    const body = samples.map((s) => s.join(',')).join('\n') + '\n';
    test.lastTrace = { kind: round.kind, iteration: round.iteration, samples: samples.slice(), keys: keyLog.slice() };
    const r = await call('/api/round/submit' + q(`&kind=${round.kind}&iteration=${round.iteration}`), body);
    if (r.status === 200) {
      enter(r.json);
      $('status').textContent = 'Saved.';
    } else if (r.status === 409 && r.json.error === 'duplicate') {
      join();  // saved before (an earlier attempt's answer was lost): carry on
    } else {
      $('status').textContent = 'This round could not be saved (' + (r.json.message || r.status) + '). Please play it again.';
      $('start').disabled = false;
      document.body.dataset.round = 'ready';
    }
  }

  // ---- questionnaire ----
  function buildQuestionnaire() {
    const f = $('qform');
    f.textContent = '';
    for (const item of st.items) {
      const div = document.createElement('div');
      div.className = 'item';
      const p = document.createElement('p');
      p.textContent = item.question;
      div.appendChild(p);
      const scale = document.createElement('div');
      scale.className = 'scale';
      for (let v = 1; v <= 7; v++) {
        const l = document.createElement('label');
        const i = document.createElement('input');
        i.type = 'radio'; i.name = item.name; i.value = String(v); i.id = item.name + '-' + v;
        l.appendChild(i);
        l.appendChild(document.createTextNode(String(v)));
        scale.appendChild(l);
      }
      div.appendChild(scale);
      f.appendChild(div);
    }
    if (st.yes_no) {
      const div = document.createElement('div');
      div.className = 'item';
      const p = document.createElement('p');
      p.textContent = st.yes_no.question;
      div.appendChild(p);
      const scale = document.createElement('div');
      scale.className = 'scale';
      for (const v of ['yes', 'no']) {
        const l = document.createElement('label');
        const i = document.createElement('input');
        i.type = 'radio'; i.name = st.yes_no.name; i.value = v; i.id = st.yes_no.name + '-' + v;
        l.appendChild(i);
        l.appendChild(document.createTextNode(v));
        scale.appendChild(l);
      }
      div.appendChild(scale);
      f.appendChild(div);
    }
  }
  $('qsubmit').addEventListener('click', async () => {
    const data = new FormData($('qform'));
    const names = st.items.map((i) => i.name).concat(st.yes_no ? [st.yes_no.name] : []);
    const missing = names.filter((n) => !data.get(n));
    if (missing.length) { $('qstatus').textContent = 'Please answer every question.'; return; }
    $('qsubmit').disabled = true;
    $('qstatus').textContent = 'Sending…';
    const r = await call('/api/questionnaire' + q(), new URLSearchParams(data).toString());
    $('qsubmit').disabled = false;
    if (r.status === 200 || (r.status === 409 && r.json.error === 'duplicate')) finish();
    else $('qstatus').textContent = r.json.message || 'Could not send the answers.';
  });

  function finish() {
    $('progress').textContent = 'Finished';
    show('done');
    if (st && st.completion_url) {
      $('completion-link').href = st.completion_url;
      $('completion').hidden = false;
      setTimeout(() => { location.href = st.completion_url; }, 3000);
    }
  }

  $('agree').addEventListener('click', () => { st.stage = 'rounds'; enter(st); });
  window.addEventListener('resize', () => { if (st && !$('game').hidden) draw(); });
  join();
})();
