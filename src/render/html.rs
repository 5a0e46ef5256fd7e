//! A self-contained HTML page that animates the plan: play / pause and a time slider, no
//! network needed. Frames are precomputed (outlines in pixels) and embedded as JSON.

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
    format!(
        r##"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{title}: plan</title>
<style>
body {{ font-family: sans-serif; margin: 16px; }}
#controls {{ display: flex; gap: 12px; align-items: center; margin-bottom: 8px; }}
#time {{ width: 420px; }}
</style></head>
<body>
<h3>{title}</h3>{legend}
<div id="controls"><button id="play">Play</button><input id="time" type="range" min="0" max="{last}" value="0" step="1"><span id="clock">0.00 s</span></div>
<svg id="view" xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}"></svg>
<script>
const frames = {frames};
const table = "{table}";
const goal = {goal};
const names = [{names}];
const colours = [{colours}];
const svg = document.getElementById("view");
const NS = "http://www.w3.org/2000/svg";
function add(tag, attrs) {{
  const e = document.createElementNS(NS, tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  svg.appendChild(e);
  return e;
}}
function draw(n) {{
  const f = frames[n];
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  add("polygon", {{class: "table", points: table, fill: "#f2ead8", stroke: "#b9a77f"}});
  if (goal) add("circle", {{class: "goal", cx: goal[0], cy: goal[1], r: goal[2], fill: "{goal_colour}", "fill-opacity": 0.15, stroke: "{goal_colour}"}});
  f.objects.forEach((p, i) => add("polygon", {{class: "object", "data-object": names[i], points: p, fill: colours[i], "fill-opacity": 0.85, stroke: "#222"}}));
  f.executed.forEach((p, i) => add("polygon", {{class: "executed", "data-object": names[i], points: p, fill: "none", stroke: "#111", "stroke-width": 1.5, "stroke-dasharray": "5 3"}}));
  f.links.forEach(([p, hot]) => add("polygon", {{class: hot ? "link contact" : "link", points: p, fill: hot ? "{contact}" : "#9aa3ad", "fill-opacity": 0.75, stroke: "#333"}}));
  document.getElementById("clock").textContent = f.t.toFixed(2) + " s";
  document.getElementById("time").value = n;
  document.body.dataset.frame = n;
}}
let playing = null;
const button = document.getElementById("play");
function stop() {{ clearInterval(playing); playing = null; button.textContent = "Play"; }}
button.addEventListener("click", () => {{
  if (playing) return stop();
  let n = Number(document.getElementById("time").value);
  if (n >= frames.length - 1) n = 0;
  button.textContent = "Pause";
  playing = setInterval(() => {{ draw(n); if (++n >= frames.length) stop(); }}, 40);
}});
document.getElementById("time").addEventListener("input", e => {{ stop(); draw(Number(e.target.value)); }});
draw(0);
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
    )
}
