//! A self-contained HTML page that animates the plan, no network needed: a 3D view (the
//! project's own WebGL viewer, [`super::webgl`]) with the objects' names, a legend, a scale
//! bar and trails, and a top view below it; play / pause at true speed or at a chosen
//! speed, a time slider and a time readout. Frames are precomputed and embedded as JSON.

use super::svg::{escape, object_colour, View};
use super::Film;
use nalgebra::Vector2;
use std::fmt::Write;

/// At most this many frames are embedded (steps are subsampled evenly).
const MAX_FRAMES: usize = 400;

fn points(view: &View, polygon: &[Vector2<f64>]) -> String {
    format!("\"{}\"", view.points(polygon))
}

/// `s` as a JavaScript string literal inside a `<script>` block: JSON, with `<`, `>`
/// and `&` written as escapes so that no name can close the block (`</script>`).
fn js_string(s: &str) -> String {
    serde_json::to_string(s)
        .expect("strings serialise")
        .replace('<', "\\u003c")
        .replace('>', "\\u003e")
        .replace('&', "\\u0026")
}

pub fn animation(film: &Film) -> String {
    let view = View::of(film);
    let steps = film.states.len();
    let stride = steps.div_ceil(MAX_FRAMES).max(1);
    let mut indices: Vec<usize> = (0..steps).step_by(stride).collect();
    if *indices.last().unwrap() != steps - 1 {
        indices.push(steps - 1);
    }
    let mut frames = String::from("[");
    for (n, &k) in indices.iter().enumerate() {
        let frame = film.frame(k);
        let links: Vec<String> = frame
            .links
            .iter()
            .map(|(o, hot)| format!("[{},{}]", points(&view, o), u8::from(*hot)))
            .collect();
        let objects: Vec<String> = frame.objects.iter().map(|o| points(&view, o)).collect();
        let executed: Vec<String> = frame.executed.iter().map(|o| points(&view, o)).collect();
        let _ = write!(
            frames,
            "{}{{\"t\":{:.3},\"links\":[{}],\"objects\":[{}],\"executed\":[{}]}}",
            if n > 0 { "," } else { "" },
            frame.time,
            links.join(","),
            objects.join(","),
            executed.join(",")
        );
    }
    frames.push(']');
    let t = &film.scene.table;
    let table = [
        Vector2::new(t.x.1, t.y.1),
        Vector2::new(t.x.1, t.y.0),
        Vector2::new(t.x.0, t.y.0),
        Vector2::new(t.x.0, t.y.1),
    ];
    let goal = film.goal_disc().map_or("null".to_string(), |(c, r)| {
        let (u, v) = view.px(&c);
        format!("[{u:.1},{v:.1},{:.1}]", r * super::svg::SCALE)
    });
    let names: Vec<String> = film
        .scene
        .objects
        .iter()
        .map(|o| js_string(&o.name))
        .collect();
    let colours: Vec<String> = (0..film.scene.objects.len())
        .map(|i| js_string(object_colour(film, i)))
        .collect();
    let title = escape(&film.scene.name);
    let scene3d = super::webgl::scene_json(film, &indices);
    let goal_object = film.scene.goal.object();
    let mut legend3d =
        String::from("<li><span class=\"swatch\" style=\"background:#9aa3ad\"></span>arm</li>");
    let _ = write!(
        legend3d,
        "<li><span class=\"swatch\" style=\"background:{}\"></span>a link pushing an object; the line: the tool's path</li>",
        super::svg::CONTACT_COLOUR
    );
    for (i, o) in film.scene.objects.iter().enumerate() {
        let _ = write!(
            legend3d,
            "<li><span class=\"swatch\" style=\"background:{}\"></span>{}{}</li>",
            object_colour(film, i),
            escape(&o.name),
            if goal_object == Some(i) {
                " (the goal object)"
            } else {
                ""
            }
        );
    }
    if film.goal_disc().is_some() {
        let _ = write!(
            legend3d,
            "<li><span class=\"swatch\" style=\"background:{};opacity:0.4\"></span>the goal region</li>",
            super::svg::GOAL_REGION_COLOUR
        );
    }
    if !film.executed.is_empty() {
        legend3d.push_str("<li><span class=\"swatch\" style=\"background:#1a1a1a;opacity:0.4\"></span>where the 3D execution took the objects</li>");
    }
    legend3d.push_str("<li><span class=\"swatch\" style=\"background:#1a1a1a;height:3px\"></span>the objects' paths so far (lines on the table); the black bar is 20 cm</li>");
    let duration = film.states.len().saturating_sub(1) as f64 * film.dt;
    format!(
        r##"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{title}: plan</title>
<style>
body {{ font-family: sans-serif; margin: 16px; }}
#controls {{ display: flex; gap: 12px; align-items: center; margin-bottom: 8px; }}
#time {{ width: 420px; }}
#stage {{ position: relative; width: 900px; height: 520px; border: 1px solid #ccc; }}
#view3d {{ cursor: grab; }}
.label {{ position: absolute; transform: translate(-50%, -100%); font-size: 12px; background: rgba(255,255,255,0.75); padding: 0 3px; pointer-events: none; white-space: nowrap; }}
.legend {{ list-style: none; padding: 0; columns: 2; font-size: 13px; }}
.swatch {{ display: inline-block; width: 14px; height: 10px; margin-right: 6px; border: 1px solid #555; vertical-align: middle; }}
</style></head>
<body>
<h3>{title}</h3>{legend}
<div id="controls"><button id="play">Play</button><input id="time" type="range" min="0" max="{last}" value="0" step="1"><span id="clock">0.00 s</span>
<label>speed <select id="speed"><option value="0.25">0.25x</option><option value="0.5">0.5x</option><option value="1" selected>1x (true speed)</option><option value="2">2x</option><option value="4">4x</option></select></label></div>
<div id="stage"><canvas id="view3d" width="900" height="520"></canvas><div id="labels"></div></div>
<p id="view3d-note">3D view: drag to turn, the wheel to come closer.</p>
<ul class="legend">{legend3d}</ul>
<h4>Top view</h4>
<svg id="view" xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}"></svg>
<script>
const frames = {frames};
const table = "{table}";
const goal = {goal};
const names = [{names}];
const colours = [{colours}];
const CONTACT = "{contact}";
const GOAL_REGION = "{goal_colour}";
const S3 = {scene3d};
{viewer}
const svg = document.getElementById("view");
const NS = "http://www.w3.org/2000/svg";
function add(tag, attrs) {{
  const e = document.createElementNS(NS, tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  svg.appendChild(e);
  return e;
}}
let current = 0;
function draw(n) {{
  current = n;
  const f = frames[n];
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  add("polygon", {{class: "table", points: table, fill: "#f2ead8", stroke: "#b9a77f"}});
  if (goal) add("circle", {{class: "goal", cx: goal[0], cy: goal[1], r: goal[2], fill: "{goal_colour}", "fill-opacity": 0.15, stroke: "{goal_colour}"}});
  f.objects.forEach((p, i) => add("polygon", {{class: "object", "data-object": names[i], points: p, fill: colours[i], "fill-opacity": 0.85, stroke: "#222"}}));
  f.executed.forEach((p, i) => add("polygon", {{class: "executed", "data-object": names[i], points: p, fill: "none", stroke: "#111", "stroke-width": 1.5, "stroke-dasharray": "5 3"}}));
  f.links.forEach(([p, hot]) => add("polygon", {{class: hot ? "link contact" : "link", points: p, fill: hot ? "{contact}" : "#9aa3ad", "fill-opacity": 0.75, stroke: "#333"}}));
  view3d(n);
  document.getElementById("clock").textContent = f.t.toFixed(2) + " s of {duration:.2} s";
  document.getElementById("time").value = n;
  document.body.dataset.frame = n;
}}
// Playback in real time times the chosen speed: the frame shown is the last one due.
let playing = false, started = 0, from = 0;
const button = document.getElementById("play"), speed = document.getElementById("speed");
function due(t) {{ let n = current; while (n + 1 < frames.length && frames[n + 1].t <= t) n++; return n; }}
function tick(now) {{
  if (!playing) return;
  const n = due(from + (now - started) / 1000 * Number(speed.value));
  if (n !== current) draw(n);
  if (n >= frames.length - 1) return stop();
  requestAnimationFrame(tick);
}}
function stop() {{ playing = false; button.textContent = "Play"; }}
function restart() {{ from = frames[current].t; started = performance.now(); }}
button.addEventListener("click", () => {{
  if (playing) return stop();
  if (current >= frames.length - 1) draw(0);
  playing = true; button.textContent = "Pause"; restart(); requestAnimationFrame(tick);
}});
speed.addEventListener("change", restart);
document.getElementById("time").addEventListener("input", e => {{ stop(); draw(Number(e.target.value)); }});
// animation.html#t=2.5 opens at 2.5 s.
const opening = /t=([0-9.]+)/.exec(location.hash);
draw(opening ? due(Number(opening[1])) : 0);
</script>
</body></html>
"##,
        last = indices.len() - 1,
        legend = if film.executed.is_empty() {
            ""
        } else {
            "<p>Filled: the objects as the plan predicts them; dashed black outlines: where the 3D execution took them.</p>"
        },
        w = view.width,
        h = view.height,
        table = view.points(&table),
        names = names.join(","),
        colours = colours.join(","),
        contact = super::svg::CONTACT_COLOUR,
        goal_colour = super::svg::GOAL_REGION_COLOUR,
        viewer = super::webgl::VIEWER,
    )
}
