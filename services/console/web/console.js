// SSL match console: the browser page. Plain ES2020, no framework, no build step.
//
// Contract: PROTOCOL.md beside web/. One EventSource on /events (hello, geometry, frame, referee, event,
// log, health, params, report) and JSON POSTs to /api/* carrying the URL's ?token= as X-Console-Token.
// Everything received is in the SSL-Vision GLOBAL frame: metres, radians, x towards the positive goal,
// y up. The canvas flips y. Teams are colours (blue/yellow), never "ours".
//
// Test hooks (stable): window.sslConsole = { frames, drawn, toCanvas(x,y), toField(px,py), state }.
'use strict';

(() => {
  // ===================================================================================================
  // Small helpers
  // ===================================================================================================
  const $ = (sel, root = document) => root.querySelector(sel);
  const $$ = (sel, root = document) => Array.from(root.querySelectorAll(sel));
  const esc = (v) => String(v ?? '').replace(/[&<>"']/g, (c) => (
    { '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c]));
  const num = (v, digits = 1) => (typeof v === 'number' && Number.isFinite(v) ? v.toFixed(digits) : '—');
  const pad2 = (n) => String(n).padStart(2, '0');

  /** Seconds -> "mm:ss", negative with a leading minus (stage time left may run over). */
  function fmtClock(s) {
    if (typeof s !== 'number' || !Number.isFinite(s)) return '—';
    const neg = s < 0;
    const a = Math.floor(Math.abs(s));
    return `${neg ? '-' : ''}${pad2(Math.floor(a / 60))}:${pad2(a % 60)}`;
  }
  /** Seconds -> "1h02m" / "3m05s" / "12s". */
  function fmtDuration(s) {
    if (typeof s !== 'number' || !Number.isFinite(s)) return '—';
    const a = Math.floor(s);
    if (a >= 3600) return `${Math.floor(a / 3600)}h${pad2(Math.floor((a % 3600) / 60))}m`;
    if (a >= 60) return `${Math.floor(a / 60)}m${pad2(a % 60)}s`;
    return `${a}s`;
  }
  /** unix_ns -> local "hh:mm:ss". */
  function fmtTime(ns) {
    const d = new Date(Number(ns) / 1e6);
    if (Number.isNaN(d.getTime())) return '--:--:--';
    return `${pad2(d.getHours())}:${pad2(d.getMinutes())}:${pad2(d.getSeconds())}`;
  }
  const fmtXY = (p) => (Array.isArray(p) && p.length >= 2 ? `(${num(p[0], 2)}, ${num(p[1], 2)}) m` : '—');
  /** "PREPARE_KICKOFF_YELLOW" -> "KICKOFF YELLOW". */
  const prettyCommand = (c) => (c ? String(c).replace(/^PREPARE_/, '').replace(/_/g, ' ') : '—');
  const prettyStage = (s) => (s ? String(s).replace(/_/g, ' ').toLowerCase() : '—');
  const TEAMS = ['blue', 'yellow'];
  const teamLabel = (t) => (t === 'blue' ? 'Blue' : t === 'yellow' ? 'Yellow' : String(t ?? ''));

  function store(key, value) {
    try { localStorage.setItem(`sslConsole.${key}`, JSON.stringify(value)); } catch (_) { /* private mode */ }
  }
  function load(key, fallback) {
    try {
      const v = localStorage.getItem(`sslConsole.${key}`);
      return v === null ? fallback : JSON.parse(v);
    } catch (_) { return fallback; }
  }

  // ===================================================================================================
  // State (latest of every stream event, as received) and the test hook
  // ===================================================================================================
  const DEFAULT_GEOMETRY = {  // division B, used until the server's `geometry` arrives
    field_length: 9, field_width: 6, goal_width: 1, goal_depth: 0.18, boundary_width: 0.3,
    penalty_area_depth: 1, penalty_area_width: 2, center_circle_radius: 0.5,
    ball_radius: 0.0215, robot_radius: 0.09,
  };
  const state = {
    hello: null,      // {version, operator, simulator, profile}
    geometry: null,   // see DEFAULT_GEOMETRY
    referee: null,    // REFEREE
    health: null,     // HEALTH
    params: null,     // {"params":[PARAM...]} as received
    report: null,     // REPORT
    frame: null,      // the newest FRAME (older ones are dropped, never queued)
    log: [],          // ENTRY[], newest first, at most 20
  };
  const hook = {
    frames: 0,        // number of `frame` events received
    draws: 0,         // number of canvas redraws (bench/console_load: the page's frames per second)
    drawn: [],        // what the last draw put on the canvas
    toCanvas: (x, y) => toCanvas(x, y),
    toField: (px, py) => toField(px, py),
    state,
  };
  window.sslConsole = hook;

  const canOperate = () => !!(state.hello && state.hello.operator);
  const canPlace = () => !!(state.hello && state.hello.operator && state.hello.simulator);
  const geometry = () => state.geometry || DEFAULT_GEOMETRY;

  // ===================================================================================================
  // Toasts and POSTs. Token: read once from ?token=, sent as X-Console-Token on every POST.
  // Answers are {"ok":true} or {"ok":false,"error":"why"} (400/403/503).
  // ===================================================================================================
  const TOKEN = new URLSearchParams(location.search).get('token');

  function toast(text, kind = 'info', ms = 3500) {
    const el = document.createElement('div');
    el.className = `toast ${kind}`;
    el.textContent = text;
    $('#toasts').prepend(el);
    while ($('#toasts').children.length > 5) $('#toasts').lastElementChild.remove();
    setTimeout(() => el.remove(), ms);
  }

  /** POST JSON; resolves to {ok, status, data}; shows the server's error in a toast. */
  async function post(path, body, { quiet = false } = {}) {
    const headers = { 'Content-Type': 'application/json' };
    if (TOKEN !== null) headers['X-Console-Token'] = TOKEN;
    let res;
    try {
      res = await fetch(path, { method: 'POST', headers, body: JSON.stringify(body) });
    } catch (err) {
      toast(`${path}: network error (${err.message})`, 'err', 5000);
      return { ok: false, status: 0, data: { ok: false, error: 'network error' } };
    }
    let data = null;
    try { data = await res.json(); } catch (_) { data = { ok: false, error: `HTTP ${res.status}` }; }
    const ok = res.ok && data && data.ok === true;
    if (!ok && !quiet) toast(`${res.status} ${path}: ${(data && data.error) || 'failed'}`, 'err', 6000);
    return { ok, status: res.status, data: data || {} };
  }

  // ===================================================================================================
  // Stream. EventSource reconnects by itself after network errors; if it gives up (readyState CLOSED,
  // e.g. the server answered an error while restarting) it is recreated after 1 s. A watchdog also
  // recreates it when an OPEN stream stays silent for 6 s (health comes at 1 Hz).
  // ===================================================================================================
  let source = null;
  let lastMessageAt = 0;
  let reconnectTimer = null;

  function setConnected(open) {
    const dot = $('#conn');
    dot.classList.toggle('open', open);
    dot.title = open ? 'stream connected' : 'stream disconnected (reconnecting)';
    document.body.classList.toggle('offline', !open);
  }

  function connect() {
    if (reconnectTimer) { clearTimeout(reconnectTimer); reconnectTimer = null; }
    if (source) source.close();
    // EventSource cannot send headers: the token rides in the query, so that hello.operator is ours.
    const es = new EventSource(TOKEN ? `/events?token=${encodeURIComponent(TOKEN)}` : '/events');
    source = es;
    lastMessageAt = performance.now();
    es.onopen = () => { if (source === es) { setConnected(true); lastMessageAt = performance.now(); } };
    es.onerror = () => {
      if (source !== es) return;
      setConnected(false);
      if (es.readyState === EventSource.CLOSED && !reconnectTimer) reconnectTimer = setTimeout(connect, 1000);
    };
    for (const [name, handler] of Object.entries(HANDLERS)) {
      es.addEventListener(name, (ev) => {
        if (source !== es) return;
        lastMessageAt = performance.now();
        let data;
        try { data = JSON.parse(ev.data); } catch (err) { console.warn(`bad ${name} message`, err); return; }
        handler(data);
      });
    }
  }

  setInterval(() => {
    if (source && source.readyState === EventSource.OPEN && performance.now() - lastMessageAt > 6000) {
      setConnected(false);
      connect();
    }
  }, 1000);

  const HANDLERS = {
    hello(d) {
      if (d.version !== 1) toast(`server speaks protocol version ${d.version}, this page expects 1`, 'err', 10000);
      state.hello = d;
      renderHello();
    },
    geometry(d) { state.geometry = d; resizeCanvas(); },
    frame(d) { hook.frames += 1; state.frame = d; requestDraw(); scheduleTeams(); },
    referee(d) { state.referee = d; renderReferee(); requestDraw(); },
    log(d) { state.log = (d.entries || []).slice(0, 20); renderLog(); },
    event(d) { state.log.unshift(d); state.log.length = Math.min(state.log.length, 20); renderLog(); },
    health(d) { state.health = d; renderHealth(); },
    params(d) { state.params = d; renderParams(); },
    report(d) { state.report = d; renderReport(); },
  };

  // ===================================================================================================
  // Header: hello (badges, permissions), scoreboard, referee status
  // ===================================================================================================
  function renderHello() {
    const h = state.hello || {};
    $('#readonly-badge').hidden = !!h.operator;
    $('#sim-badge').hidden = !h.simulator;
    renderProfile();
    applyPermissions();
  }

  /** Enable/disable every operator control from hello.operator (read-only page when false). */
  function applyPermissions() {
    const op = canOperate();
    for (const b of $$('#operator-panel button[data-command], #pick-target, #clear-target')) b.disabled = !op;
    $('#estop').disabled = !op;
    $('#estop-release').disabled = !op;
    for (const el of $$('#params .param-value, #params button')) el.disabled = !op;
    if (!op) setPicking(false);
    updateFieldHint();
  }

  function commandClass(cmd) {
    if (!cmd) return 'cmd-none';
    if (cmd === 'HALT') return 'cmd-halt';
    if (cmd === 'STOP') return 'cmd-stop';
    if (cmd === 'NORMAL_START' || cmd === 'FORCE_START') return 'cmd-go';
    if (cmd.endsWith('_YELLOW')) return 'cmd-yellow';
    if (cmd.endsWith('_BLUE')) return 'cmd-blue';
    return 'cmd-none';
  }

  function cardsHtml(t) {
    let html = '';
    if (t.yellow_cards > 0) html += `<span class="card yc" title="yellow cards">${t.yellow_cards}</span>`;
    if (t.red_cards > 0) html += `<span class="card rc" title="red cards">${t.red_cards}</span>`;
    html += `<span class="gk" title="goalkeeper id · timeouts left">GK ${esc(t.goalkeeper ?? '?')} · TO ${esc(t.timeouts ?? '?')}</span>`;
    return html;
  }

  function renderReferee() {
    const r = state.referee;
    if (!r) return;
    for (const t of TEAMS) {
      const info = r[t] || {};
      $(`#${t}-name`).textContent = info.name || teamLabel(t);
      $(`#${t}-score`).textContent = info.score ?? 0;
      $(`#${t}-cards`).innerHTML = cardsHtml(info);
    }
    const cmd = $('#ref-command');
    cmd.textContent = prettyCommand(r.command);
    cmd.title = `current command: ${r.command || '—'} (#${r.command_counter ?? '?'})`;
    cmd.dataset.current = r.command || '';
    cmd.className = `ref-command ${commandClass(r.command)}`;
    $('#ref-next').textContent = r.next_command ? prettyCommand(r.next_command) : '—';
    $('#ref-stage').textContent = prettyStage(r.stage);
    $('#ref-time').textContent = fmtClock(r.stage_time_left);
    $('#ref-designated').textContent = fmtXY(r.designated);
    $('#ref-source').textContent = r.source === 'gc' ? 'Game Controller' : r.source === 'builtin' ? 'built-in' : (r.source || '—');
    $('#ref-message').textContent = r.status_message || '';
    $('#ref-message').title = r.status_message || '';
    for (const b of $$('#operator-panel button[data-command]')) b.classList.toggle('current', b.dataset.command === r.command);
    updateTargetInfo();
  }

  // ===================================================================================================
  // Field view. Vision frame (m, x right, y up) -> canvas CSS px: px = cx + x*scale, py = cy - y*scale.
  // The canvas fills #field-wrap; the field (incl. boundary) is centred with its aspect ratio kept.
  // Only the newest frame is drawn, from requestAnimationFrame, when something changed.
  // ===================================================================================================
  const canvas = $('#field');
  const ctx = canvas.getContext('2d');
  const view = { w: 0, h: 0, dpr: 1, scale: 50, cx: 0, cy: 0 };

  const COLORS = {
    carpet: '#1d5e2e', field: '#217035', line: 'rgba(255,255,255,0.85)', blue: '#2f7dff', yellow: '#f2d43a',
    ball: '#ff8c1a', neutral: '#9aa0aa', keepOut: 'rgba(229,72,77,0.17)', keepOutLine: 'rgba(229,72,77,0.75)',
  };
  // How each robot source is drawn, so the two filtered views can be told apart when both are on.
  const SOURCE_STYLE = {
    blue: { outline: '#eaf2ff', dash: [], alpha: 1, width: 1.5 },
    yellow: { outline: '#fff1a8', dash: [3, 2], alpha: 0.7, width: 1.5 },
    vision: { outline: '#202020', dash: [], alpha: 0.9, width: 1 },
  };

  function toCanvas(x, y) { return { x: view.cx + x * view.scale, y: view.cy - y * view.scale }; }
  function toField(px, py) { return { x: (px - view.cx) / view.scale, y: (view.cy - py) / view.scale }; }

  function resizeCanvas() {
    const wrap = $('#field-wrap');
    const w = Math.max(1, wrap.clientWidth);
    const h = Math.max(1, wrap.clientHeight);
    const dpr = window.devicePixelRatio || 1;
    if (canvas.style.width !== `${w}px`) canvas.style.width = `${w}px`;
    if (canvas.style.height !== `${h}px`) canvas.style.height = `${h}px`;
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(h * dpr);
    const g = geometry();
    const totalL = g.field_length + 2 * g.boundary_width;
    const totalW = g.field_width + 2 * g.boundary_width;
    Object.assign(view, {
      w, h, dpr,
      scale: Math.max(1e-3, Math.min((w - 8) / totalL, (h - 8) / totalW)),
      cx: w / 2, cy: h / 2,
    });
    requestDraw();
  }

  let drawPending = false;
  function requestDraw() {
    if (drawPending) return;
    drawPending = true;
    requestAnimationFrame(() => {
      drawPending = false;
      if ((window.devicePixelRatio || 1) !== view.dpr) resizeCanvas();
      try { draw(); } catch (err) { console.error('draw failed', err); }
    });
  }

  // ---- layers (checkboxes, persisted in localStorage) ----
  const LAYER_DEFAULTS = {
    vision: false, blueWorld: true, yellowWorld: false, robots: true, ball: true,
    designated: true, keepOut: true, paths: true, roles: true,
  };
  const layers = { ...LAYER_DEFAULTS, ...load('layers', {}) };
  for (const box of $$('#layers input[data-layer]')) {
    box.checked = !!layers[box.dataset.layer];
    box.addEventListener('change', () => {
      layers[box.dataset.layer] = box.checked;
      store('layers', layers);
      requestDraw();
    });
  }

  /**
   * Which worlds robots + ball are drawn from: the checked filtered worlds that are present; if none of
   * the checked ones is present, the first present of blue's, yellow's; else raw vision. With neither
   * filtered world checked, raw vision.
   */
  function robotSources(frame) {
    const teams = (frame && frame.teams) || {};
    const checked = TEAMS.filter((t) => layers[`${t}World`]);
    if (checked.length === 0) return ['vision'];
    const present = checked.filter((t) => teams[t]);
    if (present.length) return present;
    const any = TEAMS.filter((t) => teams[t]);
    return any.length ? [any[0]] : ['vision'];
  }

  /** Robots and balls of one source, normalised: {robots:[{team,id,x,y,a,vx,vy,visible}], balls:[...]} */
  function sourceObjects(frame, src) {
    if (src === 'vision') {
      const v = frame.vision || {};
      return {
        robots: (v.robots || []).map((r) => ({ ...r, visible: true })),
        balls: (v.balls || []).map((b) => ({ ...b, visible: true })),
      };
    }
    const t = frame.teams[src];
    return { robots: t.robots || [], balls: t.ball ? [t.ball] : [] };
  }

  function line(x1, y1, x2, y2) {
    const a = toCanvas(x1, y1);
    const b = toCanvas(x2, y2);
    ctx.beginPath();
    ctx.moveTo(a.x, a.y);
    ctx.lineTo(b.x, b.y);
    ctx.stroke();
  }
  function rectField(x1, y1, x2, y2) {  // axis-aligned rectangle in metres -> canvas path
    const a = toCanvas(Math.min(x1, x2), Math.max(y1, y2));
    ctx.rect(a.x, a.y, Math.abs(x2 - x1) * view.scale, Math.abs(y2 - y1) * view.scale);
  }

  function drawField() {
    const g = geometry();
    const L = g.field_length / 2;
    const W = g.field_width / 2;
    const B = g.boundary_width;
    ctx.fillStyle = COLORS.carpet;
    ctx.beginPath(); rectField(-L - B, -W - B, L + B, W + B); ctx.fill();
    ctx.fillStyle = COLORS.field;
    ctx.beginPath(); rectField(-L, -W, L, W); ctx.fill();

    ctx.strokeStyle = COLORS.line;
    ctx.lineWidth = Math.max(1, Math.min(2, 0.01 * view.scale * 1.5));
    ctx.setLineDash([]);
    ctx.beginPath(); rectField(-L, -W, L, W); ctx.stroke();
    line(0, -W, 0, W);
    line(-L, 0, L, 0);
    ctx.globalAlpha = 0.35; line(-L, 0, L, 0); ctx.globalAlpha = 1;
    const c = toCanvas(0, 0);
    ctx.beginPath(); ctx.arc(c.x, c.y, g.center_circle_radius * view.scale, 0, 2 * Math.PI); ctx.stroke();
    ctx.fillStyle = COLORS.line;
    ctx.beginPath(); ctx.arc(c.x, c.y, 2, 0, 2 * Math.PI); ctx.fill();
    for (const s of [-1, 1]) {  // defense areas
      ctx.beginPath();
      rectField(s * L, -g.penalty_area_width / 2, s * (L - g.penalty_area_depth), g.penalty_area_width / 2);
      ctx.stroke();
    }
    // Goals: blue defends positive x when blue_on_positive_half, else negative; unknown -> neutral grey.
    const bPos = state.referee ? state.referee.blue_on_positive_half : null;
    for (const s of [-1, 1]) {
      let color = COLORS.neutral;
      if (bPos === true || bPos === false) color = (s > 0) === bPos ? COLORS.blue : COLORS.yellow;
      const gw = g.goal_width / 2;
      const a = toCanvas(s * L, -gw);
      const b = toCanvas(s * (L + g.goal_depth), -gw);
      const cc = toCanvas(s * (L + g.goal_depth), gw);
      const d = toCanvas(s * L, gw);
      ctx.strokeStyle = color;
      ctx.lineWidth = 3;
      ctx.beginPath(); ctx.moveTo(a.x, a.y); ctx.lineTo(b.x, b.y); ctx.lineTo(cc.x, cc.y); ctx.lineTo(d.x, d.y);
      ctx.stroke();
    }
    ctx.lineWidth = 1;
  }

  function drawKeepOut(zones) {
    for (const z of zones || []) {
      const r = (z.radius || 0) * view.scale;
      ctx.beginPath();
      if (z.kind === 'circle' && Array.isArray(z.center)) {
        const c = toCanvas(z.center[0], z.center[1]);
        ctx.arc(c.x, c.y, r, 0, 2 * Math.PI);
      } else if (z.kind === 'stadium' && Array.isArray(z.a) && Array.isArray(z.b)) {
        const a = toCanvas(z.a[0], z.a[1]);
        const b = toCanvas(z.b[0], z.b[1]);
        const ang = Math.atan2(b.y - a.y, b.x - a.x);
        ctx.arc(b.x, b.y, r, ang - Math.PI / 2, ang + Math.PI / 2);
        ctx.arc(a.x, a.y, r, ang + Math.PI / 2, ang + 1.5 * Math.PI);
        ctx.closePath();
      } else continue;
      ctx.fillStyle = COLORS.keepOut;
      ctx.fill();
      ctx.strokeStyle = z.team === 'blue' ? COLORS.blue : z.team === 'yellow' ? COLORS.yellow : COLORS.keepOutLine;
      ctx.setLineDash([5, 4]);
      ctx.lineWidth = 1.2;
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }

  function drawCross(x, y, sizeM, color, width = 2.5) {
    const c = toCanvas(x, y);
    const s = Math.max(6, sizeM * view.scale);
    ctx.strokeStyle = color;
    ctx.lineWidth = width;
    ctx.beginPath();
    ctx.moveTo(c.x - s, c.y - s); ctx.lineTo(c.x + s, c.y + s);
    ctx.moveTo(c.x + s, c.y - s); ctx.lineTo(c.x - s, c.y + s);
    ctx.stroke();
    ctx.lineWidth = 1;
  }

  function drawPaths(frame) {
    for (const t of TEAMS) {
      const team = frame.teams && frame.teams[t];
      if (!team) continue;
      const color = t === 'blue' ? '#7fb0ff' : '#ffe680';
      for (const p of team.paths || []) {
        const pts = p.points || [];
        ctx.strokeStyle = color;
        ctx.globalAlpha = 0.75;
        ctx.lineWidth = 1.3;
        ctx.setLineDash([4, 3]);
        if (pts.length > 1) {
          ctx.beginPath();
          pts.forEach(([x, y], i) => { const c = toCanvas(x, y); if (i) ctx.lineTo(c.x, c.y); else ctx.moveTo(c.x, c.y); });
          ctx.stroke();
        }
        ctx.setLineDash([]);
        if (Array.isArray(p.destination)) {
          const d = toCanvas(p.destination[0], p.destination[1]);
          const s = Math.max(3, 0.04 * view.scale);
          ctx.strokeRect(d.x - s, d.y - s, 2 * s, 2 * s);
        }
        ctx.globalAlpha = 1;
      }
    }
    ctx.lineWidth = 1;
  }

  function drawRobot(r, src, alphaScale = 1) {
    const g = geometry();
    const c = toCanvas(r.x, r.y);
    const rad = Math.max(4, g.robot_radius * view.scale);
    const st = SOURCE_STYLE[src] || SOURCE_STYLE.vision;
    ctx.globalAlpha = st.alpha * alphaScale * (r.visible === false ? 0.4 : 1);
    ctx.fillStyle = r.team === 'yellow' ? COLORS.yellow : COLORS.blue;
    ctx.beginPath(); ctx.arc(c.x, c.y, rad, 0, 2 * Math.PI); ctx.fill();
    ctx.strokeStyle = st.outline;
    ctx.lineWidth = st.width;
    ctx.setLineDash(st.dash);
    ctx.stroke();
    ctx.setLineDash([]);
    if (typeof r.a === 'number') {  // heading tick, sticking out of the body (vision angle, y flipped)
      const dx = Math.cos(r.a);
      const dy = -Math.sin(r.a);
      ctx.strokeStyle = r.team === 'yellow' ? '#1a1600' : '#fff';
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(c.x + dx * rad * 0.6, c.y + dy * rad * 0.6);
      ctx.lineTo(c.x + dx * rad * 1.5, c.y + dy * rad * 1.5);
      ctx.stroke();
    }
    ctx.fillStyle = r.team === 'yellow' ? '#1a1600' : '#fff';
    ctx.font = `700 ${Math.round(Math.max(9, Math.min(14, rad * 1.05)))}px system-ui, sans-serif`;
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ctx.fillText(String(r.id), c.x, c.y + 0.5);
    ctx.globalAlpha = 1;
    ctx.lineWidth = 1;
  }

  function drawBall(b, src, alphaScale = 1) {
    const g = geometry();
    const c = toCanvas(b.x, b.y);
    const rad = Math.max(4, g.ball_radius * view.scale);
    ctx.globalAlpha = alphaScale * (b.visible === false ? 0.4 : 1) * (src === 'yellow' && layers.blueWorld ? 0.8 : 1);
    ctx.fillStyle = COLORS.ball;
    ctx.beginPath(); ctx.arc(c.x, c.y, rad, 0, 2 * Math.PI); ctx.fill();
    ctx.strokeStyle = '#3a1a00';
    ctx.lineWidth = 1;
    ctx.stroke();
    const speed = Math.hypot(b.vx || 0, b.vy || 0);
    if (speed > 0.05) {  // velocity arrow: where the ball is in 0.5 s
      const e = toCanvas(b.x + b.vx * 0.5, b.y + b.vy * 0.5);
      const ang = Math.atan2(e.y - c.y, e.x - c.x);
      ctx.strokeStyle = COLORS.ball;
      ctx.fillStyle = COLORS.ball;
      ctx.lineWidth = 2;
      ctx.beginPath(); ctx.moveTo(c.x, c.y); ctx.lineTo(e.x, e.y); ctx.stroke();
      ctx.beginPath();
      ctx.moveTo(e.x, e.y);
      ctx.lineTo(e.x - 8 * Math.cos(ang - 0.4), e.y - 8 * Math.sin(ang - 0.4));
      ctx.lineTo(e.x - 8 * Math.cos(ang + 0.4), e.y - 8 * Math.sin(ang + 0.4));
      ctx.closePath(); ctx.fill();
    }
    ctx.globalAlpha = 1;
    ctx.lineWidth = 1;
  }

  function drawRawVision(frame, drawn) {
    const g = geometry();
    const v = frame.vision || {};
    ctx.lineWidth = 1.2;
    for (const r of v.robots || []) {
      const c = toCanvas(r.x, r.y);
      ctx.strokeStyle = r.team === 'yellow' ? COLORS.yellow : COLORS.blue;
      ctx.beginPath(); ctx.arc(c.x, c.y, Math.max(3, g.robot_radius * view.scale * 0.6), 0, 2 * Math.PI); ctx.stroke();
      drawn.push({ kind: 'robot', team: r.team, id: r.id, x: r.x, y: r.y, a: r.a, source: 'vision', raw: true });
    }
    ctx.strokeStyle = COLORS.ball;
    for (const b of v.balls || []) {
      const c = toCanvas(b.x, b.y);
      ctx.beginPath(); ctx.arc(c.x, c.y, 5, 0, 2 * Math.PI); ctx.stroke();
      drawn.push({ kind: 'ball', team: null, id: null, x: b.x, y: b.y, source: 'vision', raw: true });
    }
    ctx.lineWidth = 1;
  }

  function drawRoles(frame, drawn) {
    ctx.font = '600 10px system-ui, sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    const rad = geometry().robot_radius * view.scale;
    for (const t of TEAMS) {
      const team = frame.teams && frame.teams[t];
      if (!team) continue;
      for (const role of team.roles || []) {
        const r = drawn.find((d) => d.kind === 'robot' && !d.raw && d.team === t && d.id === role.id);
        if (!r) continue;
        const c = toCanvas(r.x, r.y);
        const text = role.role || '';
        const w = ctx.measureText(text).width + 6;
        ctx.fillStyle = 'rgba(0,0,0,0.55)';
        ctx.fillRect(c.x - w / 2, c.y + rad + 2, w, 13);
        ctx.fillStyle = t === 'blue' ? '#a9c8ff' : '#fff0a0';
        ctx.fillText(text, c.x, c.y + rad + 3);
      }
    }
  }

  function draw() {
    hook.draws += 1;
    ctx.setTransform(view.dpr, 0, 0, view.dpr, 0, 0);
    ctx.clearRect(0, 0, view.w, view.h);
    drawField();
    const drawn = [];
    const ref = state.referee;
    const frame = state.frame;
    if (layers.keepOut && ref) drawKeepOut(ref.keep_out);
    let sources = [];
    if (frame) {
      if (layers.paths) drawPaths(frame);
      sources = robotSources(frame);
      if (layers.vision && !sources.includes('vision')) drawRawVision(frame, drawn);
      // Draw the secondary world first so the primary one is on top.
      for (const src of [...sources].reverse()) {
        const objs = sourceObjects(frame, src);
        if (layers.robots) {
          for (const r of objs.robots) {
            drawRobot(r, src);
            drawn.push({ kind: 'robot', team: r.team, id: r.id, x: r.x, y: r.y, a: r.a, source: src });
          }
        }
        if (layers.ball) {
          for (const b of objs.balls) {
            drawBall(b, src);
            drawn.push({ kind: 'ball', team: null, id: null, x: b.x, y: b.y, source: src });
          }
        }
      }
      if (layers.roles) drawRoles(frame, drawn);
    }
    if (layers.designated && ref && Array.isArray(ref.designated)) {
      drawCross(ref.designated[0], ref.designated[1], 0.1, '#ffffff');
    }
    if (pickedTarget) {  // the operator's picked placement target
      ctx.setLineDash([3, 3]);
      drawCross(pickedTarget[0], pickedTarget[1], 0.08, '#35c4d8', 2);
      ctx.setLineDash([]);
    }
    if (drag && drag.moved) {  // ghost of the object being placed
      const from = toCanvas(drag.item.x, drag.item.y);
      const to = toCanvas(drag.x, drag.y);
      ctx.strokeStyle = 'rgba(255,255,255,0.6)';
      ctx.setLineDash([4, 4]);
      ctx.beginPath(); ctx.moveTo(from.x, from.y); ctx.lineTo(to.x, to.y); ctx.stroke();
      ctx.setLineDash([]);
      const ghost = { ...drag.item, x: drag.x, y: drag.y, vx: 0, vy: 0 };
      if (drag.item.kind === 'ball') drawBall(ghost, 'ghost', 0.55);
      else drawRobot(ghost, drag.item.source, 0.5);
    }
    hook.drawn = drawn;
    $('#draw-source').textContent = frame
      ? `robots from: ${sources.map((s) => (s === 'vision' ? 'raw vision' : `${s} world`)).join(' + ')}` : 'no frame yet';
  }

  // ---- pointer: drag to place (simulator + operator), pick a placement target ----
  let drag = null;          // {item, x, y, moved, pointerId}
  let picking = false;      // next click on the field sets pickedTarget
  let pickedTarget = null;  // [x, y] in metres, or null

  function eventToField(e) {
    const rect = canvas.getBoundingClientRect();
    return toField(e.clientX - rect.left, e.clientY - rect.top);
  }

  /** The drawn ball/robot under a field point (metres), ball first; filtered/primary before raw markers. */
  function hitTest(p) {
    const g = geometry();
    const items = hook.drawn.filter((d) => !d.raw).concat(hook.drawn.filter((d) => d.raw));
    const ballR = Math.max(g.ball_radius * 2.5, 10 / view.scale);
    for (const d of items) if (d.kind === 'ball' && Math.hypot(d.x - p.x, d.y - p.y) <= ballR) return d;
    const robotR = Math.max(g.robot_radius * 1.15, 6 / view.scale);
    let best = null;
    let bestDist = Infinity;
    for (const d of items) {
      if (d.kind !== 'robot') continue;
      const dist = Math.hypot(d.x - p.x, d.y - p.y);
      if (dist <= robotR && dist < bestDist) { best = d; bestDist = dist; }
    }
    return best;
  }

  canvas.addEventListener('pointerdown', (e) => {
    if (e.button !== 0) return;
    const p = eventToField(e);
    if (picking) {
      pickedTarget = [Number(p.x.toFixed(3)), Number(p.y.toFixed(3))];
      setPicking(false);
      updateTargetInfo();
      requestDraw();
      e.preventDefault();
      return;
    }
    if (!canPlace()) return;
    const item = hitTest(p);
    if (!item) return;
    drag = { item, x: item.x, y: item.y, moved: false, pointerId: e.pointerId };
    try { canvas.setPointerCapture(e.pointerId); } catch (_) { /* synthetic pointer */ }
    canvas.style.cursor = 'grabbing';
    e.preventDefault();
  });

  canvas.addEventListener('pointermove', (e) => {
    const p = eventToField(e);
    if (drag) {
      drag.x = p.x;
      drag.y = p.y;
      drag.moved = drag.moved || Math.hypot(p.x - drag.item.x, p.y - drag.item.y) > 0.01;
      requestDraw();
      return;
    }
    canvas.style.cursor = picking ? 'crosshair' : canPlace() && hitTest(p) ? 'grab' : 'default';
  });

  function endDrag(e, cancelled) {
    if (!drag || (e && e.pointerId !== drag.pointerId)) return;
    const d = drag;
    drag = null;
    canvas.style.cursor = 'default';
    try { canvas.releasePointerCapture(d.pointerId); } catch (_) { /* not captured */ }
    requestDraw();
    if (cancelled || !d.moved) return;
    const x = Number(d.x.toFixed(4));
    const y = Number(d.y.toFixed(4));
    const body = d.item.kind === 'ball'
      ? { object: 'ball', x, y }
      : { object: 'robot', team: d.item.team, id: d.item.id, x, y, a: typeof d.item.a === 'number' ? d.item.a : 0 };
    post('/api/place', body).then((r) => {
      if (r.ok) toast(`placed ${d.item.kind === 'ball' ? 'ball' : `${d.item.team} ${d.item.id}`} at (${x.toFixed(2)}, ${y.toFixed(2)})`, 'ok', 1500);
    });
  }
  canvas.addEventListener('pointerup', (e) => endDrag(e, false));
  canvas.addEventListener('pointercancel', (e) => endDrag(e, true));

  function setPicking(on) {
    picking = !!on;
    $('#pick-target').classList.toggle('active', picking);
    $('#pick-target').textContent = picking ? 'click the field…' : 'pick target';
    canvas.style.cursor = picking ? 'crosshair' : 'default';
    updateFieldHint();
  }

  function updateFieldHint() {
    const hint = $('#field-hint');
    if (picking) { hint.textContent = 'Click the field to set the ball placement target'; hint.hidden = false; }
    else if (canPlace()) { hint.textContent = 'Drag the ball or a robot to place it'; hint.hidden = false; }
    else hint.hidden = true;
  }

  // ===================================================================================================
  // Operator panel: each [data-command] button POSTs /api/referee {"command": NAME}; ball placement adds
  // "designated": the picked target, else the current designated position, else the field centre.
  // ===================================================================================================
  function placementTarget() {
    if (pickedTarget) return { point: pickedTarget, from: 'picked' };
    const d = state.referee && state.referee.designated;
    if (Array.isArray(d) && d.length >= 2) return { point: [d[0], d[1]], from: 'current designated' };
    return { point: [0, 0], from: 'field centre' };
  }
  function updateTargetInfo() {
    const t = placementTarget();
    $('#target-info').textContent = `target: ${fmtXY(t.point)} (${t.from})`;
    $('#clear-target').hidden = !pickedTarget;
  }

  async function sendCommand(command) {
    const body = { command };
    if (command.startsWith('BALL_PLACEMENT_')) body.designated = placementTarget().point;
    const r = await post('/api/referee', body);
    if (r.ok) toast(`${prettyCommand(command)} sent`, 'ok', 1500);
  }

  for (const b of $$('#operator-panel button[data-command]')) {
    b.addEventListener('click', () => { b.blur(); sendCommand(b.dataset.command); });
  }
  $('#pick-target').addEventListener('click', () => setPicking(!picking));
  $('#clear-target').addEventListener('click', () => { pickedTarget = null; updateTargetInfo(); requestDraw(); });

  function setAdvanced(open) {
    $('#advanced').hidden = !open;
    $('#advanced-toggle').textContent = open ? 'Advanced ▾' : 'Advanced ▸';
    $('#advanced-toggle').setAttribute('aria-expanded', String(open));
    store('advanced', open);
  }
  $('#advanced-toggle').addEventListener('click', () => setAdvanced($('#advanced').hidden));
  setAdvanced(!!load('advanced', false));

  // ===================================================================================================
  // Profile panel (hello.profile; null with the Game Controller)
  // ===================================================================================================
  function renderProfile() {
    const p = state.hello && state.hello.profile;
    const body = $('#profile-body');
    if (!state.hello) { body.innerHTML = '<span class="muted">waiting for the server…</span>'; return; }
    if (!p) {
      $('#profile-title').textContent = 'Profile';
      body.innerHTML = '<span class="muted">Game Controller: no profile</span>';
      return;
    }
    $('#profile-title').textContent = `Profile · ${p.name || '?'}`;
    body.innerHTML = (p.sections || []).map((s) => `
      <div class="profile-section"><h3>${esc(s.title)}</h3><div class="profile-rows">${
  (s.fields || []).map((f) => `<span>${esc(f.label)}</span><span class="v">${
    typeof f.on === 'boolean' ? `<span class="pill ${f.on ? 'on' : 'off'}">${f.on ? 'ON' : 'OFF'}</span>` : esc(f.value)
  }</span>`).join('')}</div></div>`).join('');
  }

  // ===================================================================================================
  // Event log: 20 newest entries, newest first
  // ===================================================================================================
  function renderLog() {
    $('#event-log').innerHTML = state.log.map((e) => `
      <li class="log-entry" data-kind="${esc(e.kind)}"><span class="t">${fmtTime(e.t)}</span>
        <span class="team-dot ${e.team === 'blue' || e.team === 'yellow' ? e.team : 'none'}"></span>
        <span class="k">${esc(e.kind)}</span><span class="txt">${esc(e.text)}</span></li>`).join('');
  }

  // ===================================================================================================
  // Match report
  // ===================================================================================================
  function renderReport() {
    const r = state.report;
    if (!r) return;
    const share = typeof r.in_play_share === 'number' ? (r.in_play_share <= 1 ? r.in_play_share * 100 : r.in_play_share) : null;
    const cells = [
      ['duration', fmtClock(r.duration_s)],
      ['score Y : B', `${r.score?.yellow ?? '—'} : ${r.score?.blue ?? '—'}`],
      ['fouls Y / B', `${r.fouls?.yellow ?? '—'} / ${r.fouls?.blue ?? '—'}`],
      ['placements', `${r.placements?.succeeded ?? '—'} / ${r.placements?.tried ?? '—'} ok`],
      ['in play', share === null ? '—' : `${share.toFixed(0)} %`],
      ['longest stall', typeof r.longest_stall_s === 'number' ? `${r.longest_stall_s.toFixed(1)} s` : '—'],
    ];
    $('#report').innerHTML = cells.map(([l, v]) => `<div class="cell"><span class="l">${esc(l)}</span><span class="v">${esc(v)}</span></div>`).join('');
  }

  // ===================================================================================================
  // Behaviour trees, roles, play/tactic per team (from frame.teams[T]); rendered at most 5 Hz
  // ===================================================================================================
  let teamsTimer = null;
  let teamsRenderedAt = 0;
  function scheduleTeams() {
    if (teamsTimer) return;
    const wait = Math.max(0, 200 - (performance.now() - teamsRenderedAt));
    teamsTimer = setTimeout(() => {
      teamsTimer = null;
      teamsRenderedAt = performance.now();
      renderTeams();
    }, wait);
  }

  function renderTeams() {
    const frame = state.frame;
    for (const t of TEAMS) {
      const el = $(`#tree-${t}`);
      const team = frame && frame.teams ? frame.teams[t] : null;
      if (!team) {
        el.innerHTML = `<div class="tt-head"><span class="tt-title">${teamLabel(t)}</span><span class="muted">no data</span></div>`;
        continue;
      }
      const roles = (team.roles || []).map((r) => `<tr><td class="num">${esc(r.id)}</td><td>${esc(r.role)}</td><td>${esc(r.tactic)}</td><td>${esc(r.skill)}</td></tr>`).join('');
      const tree = (team.tree || []).map((n) => `<div class="tnode s-${esc(n.status)}" style="padding-left:${Math.max(0, n.depth | 0) * 12}px" title="${esc(n.status)}">${esc(n.name)}</div>`).join('');
      const age = typeof team.age === 'number' ? team.age : null;
      el.innerHTML = `
        <div class="tt-head"><span class="tt-title">${teamLabel(t)}</span>
          <span>play <b>${esc(team.play || '—')}</b></span><span>tactic <b>${esc(team.tactic || '—')}</b></span>
          <span class="muted">tick ${num(team.tick_ms, 2)} ms</span>
          <span class="muted">possession ${esc(team.possession || '—')}</span>
          <span class="${age !== null && age > 0.5 ? 'lvl-warn' : 'muted'}">age ${age === null ? '—' : `${age.toFixed(2)} s`}</span></div>
        ${roles ? `<table class="grid"><thead><tr><th>id</th><th>role</th><th>tactic</th><th>skill</th></tr></thead><tbody>${roles}</tbody></table>` : '<div class="muted">no roles</div>'}
        <div class="tt-tree">${tree || '<span class="muted">no tree</span>'}</div>`;
    }
  }

  // ===================================================================================================
  // Health table, robot warnings, e-stop state (health.estop)
  // ===================================================================================================
  const STALE_AFTER_S = 3;
  function renderHealth() {
    const h = state.health || {};
    const rows = (h.services || []).map((s) => {
      const stale = typeof s.age_s === 'number' && s.age_s > STALE_AFTER_S;
      const level = stale ? 'lost' : (s.level || '?');
      return `<tr class="${stale ? 'stale' : ''}" data-service="${esc(s.service)}">
        <td>${esc(s.service)}</td><td>${esc(s.host)}</td><td class="lvl lvl-${esc(level)}">${esc(level)}</td>
        <td>${stale ? `lost (${num(s.age_s, 0)} s ago)` : esc(s.status)}</td>
        <td class="num">${num(s.rate_hz, 1)}</td><td class="num">${num(s.latency_p99_ms, 1)}</td>
        <td class="num">${esc(s.errors ?? '—')}</td><td class="num">${esc(s.dropped ?? '—')}</td>
        <td class="num">${fmtDuration(s.uptime_s)}</td></tr>`;
    }).join('');
    $('#health-table tbody').innerHTML = rows || '<tr><td colspan="9" class="muted">no services reporting</td></tr>';

    const warnings = (h.robots || []).filter((r) => r.battery_low || r.link_low || (r.age_s > STALE_AFTER_S)).map((r) => {
      const parts = [];
      if (r.battery_low) parts.push(`<span class="bad">battery ${r.battery_v === null || r.battery_v === undefined ? '?' : `${num(r.battery_v, 1)} V`} low</span>`);
      if (r.link_low) parts.push(`<span class="warn">link ${typeof r.link_quality === 'number' ? `${Math.round(r.link_quality * 100)} %` : '?'} low</span>`);
      if (r.age_s > STALE_AFTER_S) parts.push(`<span class="muted">no feedback for ${num(r.age_s, 0)} s</span>`);
      return `<li data-team="${esc(r.team)}" data-id="${esc(r.id)}"><span class="team-dot ${r.team === 'yellow' ? 'yellow' : 'blue'}" style="display:inline-block"></span>
        ${esc(teamLabel(r.team))} #${esc(r.id)}: ${parts.join(' · ')}</li>`;
    }).join('');
    $('#robot-warnings').innerHTML = warnings || '<li class="muted">no robot warnings</li>';

    const e = h.estop || {};
    const engaged = !!e.engaged;
    $('#estop-banner').hidden = !engaged;
    $('#estop-release').hidden = !engaged;
    $('#estop-detail').textContent = engaged ? `${e.source || '?'}: ${e.reason || ''}` : '';
    document.body.classList.toggle('estopped', engaged);
  }

  // ---- e-stop actions: the button and SPACE engage; only #estop-release releases ----
  function engageEstop() {
    if (!canOperate()) { toast('read-only: e-stop not allowed from this page', 'err'); return; }
    post('/api/estop', { engaged: true, reason: 'console button' }).then((r) => {
      if (r.ok) toast('E-STOP sent', 'ok', 2000);
    });
  }
  $('#estop').addEventListener('click', (e) => { e.currentTarget.blur(); engageEstop(); });
  $('#estop-release').addEventListener('click', (e) => {
    e.currentTarget.blur();
    post('/api/estop', { engaged: false, reason: 'console button' }).then((r) => {
      if (r.ok) toast('e-stop release sent', 'ok', 2000);
    });
  });

  // ===================================================================================================
  // Parameters: grouped by target; rows keyed by target+key and updated in place so an edit in progress
  // is never overwritten. Values are always sent as strings.
  // ===================================================================================================
  const paramRows = new Map();  // "target\u0000key" -> {param, tr, input, status, dirty, answer, busy}
  let paramsShape = '';

  // Types as the services' config schema names them: boolean, integer, non-negative integer, number,
  // string, "one of a, b" (then `allowed` lists the values).
  function inputFor(p) {
    if (Array.isArray(p.allowed) && p.allowed.length) {
      const select = document.createElement('select');
      select.className = 'param-value';
      for (const value of p.allowed) select.append(new Option(value, value));
      return select;
    }
    const input = document.createElement('input');
    input.className = 'param-value';
    if (p.type === 'boolean') {
      input.type = 'checkbox';
    } else if (p.type === 'number' || /integer/.test(p.type)) {
      input.type = 'number';
      input.step = /integer/.test(p.type) ? '1' : 'any';
      if (typeof p.min === 'number') input.min = String(p.min);
      if (typeof p.max === 'number') input.max = String(p.max);
    } else {
      input.type = 'text';
    }
    return input;
  }
  const inputValue = (input) => (input.type === 'checkbox' ? (input.checked ? 'true' : 'false') : input.value);
  function setInputValue(input, value) {
    if (input.type === 'checkbox') input.checked = value === true || value === 'true' || value === '1';
    else input.value = value ?? '';
  }

  function renderParamStatus(row) {
    const cell = row.status;
    const s = row.busy ? { status: 'pending', reason: '' } : (row.answer || { status: row.param.status, reason: row.param.reason });
    const status = s.status || 'ok';
    cell.className = `param-status st-${status}`;
    cell.innerHTML = `${esc(status)}${s.reason ? `<span class="reason">${esc(s.reason)}</span>` : ''}`;
    row.tr.classList.toggle('dirty', row.dirty);
  }

  async function applyParam(row) {
    if (!canOperate() || row.busy) return;
    const { target, key } = row.param;
    const value = inputValue(row.input);
    row.busy = true;
    renderParamStatus(row);
    const r = await post('/api/params', { target, key, value: String(value) }, { quiet: true });
    row.busy = false;
    if (r.status === 200 || r.data.status) {
      row.answer = { status: r.data.status || (r.ok ? 'ok' : 'rejected'), reason: r.data.reason || r.data.error || '' };
    } else {
      row.answer = { status: 'rejected', reason: r.data.error || `HTTP ${r.status}` };
      toast(`${r.status} /api/params: ${r.data.error || 'failed'}`, 'err', 6000);
    }
    if (row.answer.status === 'ok') row.dirty = false;
    renderParamStatus(row);
  }

  async function saveTarget(target, resultEl) {
    resultEl.className = 'save-result muted';
    resultEl.textContent = 'saving…';
    const r = await post('/api/params/save', { target });
    resultEl.className = `save-result ${r.ok ? 'ok' : 'err'}`;
    resultEl.textContent = r.ok ? `saved: ${r.data.file || '(no file name)'}` : `not saved: ${r.data.error || r.status}`;
  }

  function buildParams(list) {
    const root = $('#params');
    const old = paramRows;
    const rows = new Map();
    const groups = new Map();
    for (const p of list) {
      if (!groups.has(p.target)) groups.set(p.target, []);
      groups.get(p.target).push(p);
    }
    root.innerHTML = '';
    for (const [target, ps] of groups) {
      const group = document.createElement('div');
      group.className = 'param-group';
      group.dataset.target = target;
      group.innerHTML = `<div class="param-group-head"><span class="tgt">${esc(target)}</span>
        <button type="button" class="small param-save" data-target="${esc(target)}">Save</button>
        <span class="save-result"></span></div>
        <table class="grid"><thead><tr><th>key</th><th>value</th><th>status</th></tr></thead><tbody></tbody></table>`;
      const saveBtn = $('.param-save', group);
      saveBtn.addEventListener('click', () => saveTarget(target, $('.save-result', group)));
      const tbody = $('tbody', group);
      for (const p of ps) {
        const id = `${p.target}\u0000${p.key}`;
        const tr = document.createElement('tr');
        tr.className = 'param-row';
        tr.dataset.target = p.target;
        tr.dataset.key = p.key;
        const range = (typeof p.min === 'number' || typeof p.max === 'number') ? ` [${p.min ?? '−∞'} … ${p.max ?? '∞'}]` : '';
        tr.innerHTML = `<td class="param-key" title="${esc(p.type)}${esc(range)}">${esc(p.key)}
          <span class="param-desc">${esc(p.description)}${esc(range)}</span></td><td class="param-input"></td><td class="param-status"></td>`;
        const input = inputFor(p);
        const apply = document.createElement('button');
        apply.type = 'button';
        apply.className = 'small param-apply';
        apply.textContent = 'apply';
        $('.param-input', tr).append(input, ' ', apply);
        const prev = old.get(id);
        const row = { param: p, tr, input, status: $('.param-status', tr), dirty: false, answer: null, busy: false };
        if (prev && prev.dirty) { setInputValue(input, inputValue(prev.input)); row.dirty = true; row.answer = prev.answer; }
        else setInputValue(input, p.value);
        input.addEventListener('input', () => { row.dirty = true; renderParamStatus(row); });
        input.addEventListener('change', () => { row.dirty = true; renderParamStatus(row); });
        input.addEventListener('keydown', (e) => { if (e.key === 'Enter') { e.preventDefault(); applyParam(row); } });
        apply.addEventListener('click', () => applyParam(row));
        rows.set(id, row);
        renderParamStatus(row);
        tbody.append(tr);
      }
      root.append(group);
    }
    if (!list.length) root.innerHTML = '<span class="muted">no parameters</span>';
    paramRows.clear();
    for (const [k, v] of rows) paramRows.set(k, v);
  }

  function renderParams() {
    const list = (state.params && state.params.params) || [];
    const shape = list.map((p) => [p.target, p.key, p.type, p.min, p.max, p.description].join('\u0000')).join('\n');
    if (shape !== paramsShape) {
      paramsShape = shape;
      buildParams(list);
    } else {
      for (const p of list) {
        const row = paramRows.get(`${p.target}\u0000${p.key}`);
        if (!row) continue;
        if (p.revision !== row.param.revision) row.answer = null;  // the service's newer word wins
        row.param = p;
        if (!row.dirty && document.activeElement !== row.input) setInputValue(row.input, p.value);
        renderParamStatus(row);
      }
    }
    applyPermissions();
  }

  // ===================================================================================================
  // Keyboard: SPACE engages the e-stop (never releases), except while typing in a text field. Default
  // action is suppressed so a focused button (e.g. "Release e-stop") is never activated by SPACE.
  // ===================================================================================================
  function isTextEntry(el) {
    if (!el || el === document.body) return false;
    if (el.isContentEditable) return true;
    const tag = el.tagName;
    if (tag === 'TEXTAREA' || tag === 'SELECT') return true;
    if (tag !== 'INPUT') return false;
    return !['checkbox', 'radio', 'button', 'submit', 'reset', 'range', 'color', 'file'].includes(el.type);
  }
  const isSpace = (e) => e.key === ' ' || e.code === 'Space';
  document.addEventListener('keydown', (e) => {
    if (!isSpace(e) || isTextEntry(e.target)) return;
    e.preventDefault();
    e.stopPropagation();
    if (!e.repeat) engageEstop();
  }, true);
  document.addEventListener('keyup', (e) => {
    if (isSpace(e) && !isTextEntry(e.target)) { e.preventDefault(); e.stopPropagation(); }
  }, true);
  document.addEventListener('keydown', (e) => {
    if (e.key === 'Escape' && picking) setPicking(false);
    if (e.key === 'Escape' && drag) { drag = null; requestDraw(); }
  });

  // ===================================================================================================
  // Start
  // ===================================================================================================
  new ResizeObserver(() => resizeCanvas()).observe($('#field-wrap'));
  window.addEventListener('resize', resizeCanvas);
  setConnected(false);
  applyPermissions();
  renderProfile();
  renderTeams();
  renderHealth();
  updateTargetInfo();
  resizeCanvas();
  connect();
})();
