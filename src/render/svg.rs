//! SVG pictures: snapshots of the plan seen from above, and the contact timeline.
//!
//! View: the robot at the bottom looking up the table; screen up is world +x, screen
//! right is world -y. `View` maps world metres to pixels.

use super::{Film, Frame};
use nalgebra::Vector2;
use std::fmt::Write;

/// Pixels per metre.
pub const SCALE: f64 = 300.0;
const MARGIN: f64 = 20.0;

/// World (m) to panel pixels.
#[derive(Clone, Copy)]
pub struct View {
    /// The world point drawn at the panel's top-left corner: (max x, max y).
    pub x_top: f64,
    pub y_left: f64,
    pub width: f64,
    pub height: f64,
}

impl View {
    pub fn of(film: &Film) -> View {
        let t = &film.scene.table;
        let base = film.scene.robot.chain.base.translation;
        let x_low = t.x.0.min(base.x) - 0.15;
        View {
            x_top: t.x.1 + 0.05,
            y_left: t.y.1 + 0.05,
            width: (t.y.1 - t.y.0 + 0.1) * SCALE + 2.0 * MARGIN,
            height: (t.x.1 + 0.05 - x_low) * SCALE + 2.0 * MARGIN + 20.0,
        }
    }

    pub fn px(&self, p: &Vector2<f64>) -> (f64, f64) {
        (
            MARGIN + (self.y_left - p.y) * SCALE,
            MARGIN + 20.0 + (self.x_top - p.x) * SCALE,
        )
    }

    pub fn points(&self, polygon: &[Vector2<f64>]) -> String {
        polygon
            .iter()
            .map(|p| {
                let (u, v) = self.px(p);
                format!("{u:.1},{v:.1}")
            })
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// Fill colour of object `i`: the goal object dark green (as in the paper's figures),
/// the others blue, red, grey, brown, pink, cyan in order (none of them green, purple or
/// orange: those are the goal object's, the goal region's and a pushing link's).
pub fn object_colour(film: &Film, i: usize) -> &'static str {
    const PALETTE: [&str; 6] = [
        "#3b6fd8", "#d8453b", "#8c8c8c", "#8c564b", "#e377c2", "#17becf",
    ];
    match film.scene.goal.object() {
        Some(object) if object == i => GOAL_COLOUR,
        Some(object) if object < i => PALETTE[(i - 1) % PALETTE.len()],
        _ => PALETTE[i % PALETTE.len()],
    }
}

pub const GOAL_COLOUR: &str = "#1e7b1e";
/// The goal region (the disc the goal object must reach), dashed.
pub const GOAL_REGION_COLOUR: &str = "#7b3294";
/// Links in contact are highlighted.
pub const CONTACT_COLOUR: &str = "#ff7f00";
/// The arm's other links.
const LINK_COLOUR: &str = "#9aa3ad";
/// Length of the scale bar (m).
const SCALE_BAR: f64 = 0.2;
/// Height of the snapshots' header: title and legend (px).
const HEADER: f64 = 44.0;
/// Snapshots per row.
const COLUMNS: usize = 2;

/// `s` as HTML / XML text or attribute value.
pub(super) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Table, goal disc, trails up to step `k`, objects and links of `frame`.
fn panel(film: &Film, view: &View, frame: &Frame, k: usize, out: &mut String) {
    let t = &film.scene.table;
    let corners = [
        Vector2::new(t.x.1, t.y.1),
        Vector2::new(t.x.1, t.y.0),
        Vector2::new(t.x.0, t.y.0),
        Vector2::new(t.x.0, t.y.1),
    ];
    let _ = writeln!(
        out,
        r##"  <polygon class="table" points="{}" fill="#f2ead8" stroke="#b9a77f"/>"##,
        view.points(&corners)
    );
    if let Some((c, r)) = film.goal_disc() {
        let (u, v) = view.px(&c);
        let _ = writeln!(
            out,
            r##"  <circle class="goal" cx="{u:.1}" cy="{v:.1}" r="{:.1}" fill="{GOAL_REGION_COLOUR}" fill-opacity="0.12" stroke="{GOAL_REGION_COLOUR}" stroke-dasharray="4 3"/>"##,
            r * SCALE
        );
    }
    for (i, object) in film.scene.objects.iter().enumerate() {
        let trail: Vec<Vector2<f64>> = film.states[..=k]
            .iter()
            .map(|s| s.objects[i].translation())
            .collect();
        let _ = writeln!(
            out,
            r##"  <polyline class="trail" data-object="{}" points="{}" fill="none" stroke="{}" stroke-width="1.5" stroke-opacity="0.6"/>"##,
            escape(&object.name),
            view.points(&trail),
            object_colour(film, i)
        );
    }
    for (i, (object, outline)) in film.scene.objects.iter().zip(&frame.objects).enumerate() {
        let pose = film.states[k].objects[i];
        let _ = writeln!(
            out,
            r##"  <polygon class="object" data-object="{}" data-x="{}" data-y="{}" data-theta="{}" points="{}" fill="{}" fill-opacity="0.85" stroke="#222"/>"##,
            escape(&object.name),
            pose.x,
            pose.y,
            pose.theta,
            view.points(outline),
            object_colour(film, i)
        );
    }
    for (outline, hot) in &frame.links {
        let (fill, class) = if *hot {
            (CONTACT_COLOUR, "link contact")
        } else {
            (LINK_COLOUR, "link")
        };
        let _ = writeln!(
            out,
            r##"  <polygon class="{class}" points="{}" fill="{fill}" fill-opacity="0.75" stroke="#333" stroke-width="0.8"/>"##,
            view.points(outline)
        );
    }
    // Object names over the objects, haloed so they read over links and neighbours.
    for (object, outline) in film.scene.objects.iter().zip(&frame.objects) {
        let centre = outline.iter().sum::<Vector2<f64>>() / outline.len().max(1) as f64;
        let (u, v) = view.px(&centre);
        let _ = writeln!(
            out,
            r##"  <text class="name" x="{u:.1}" y="{:.1}" font-size="10" text-anchor="middle" paint-order="stroke" stroke="#fff" stroke-width="3">{}</text>"##,
            v + 3.5,
            escape(&object.name)
        );
    }
    // Scale bar, bottom left.
    let (x0, y) = (MARGIN, view.height - 10.0);
    let x1 = x0 + SCALE_BAR * SCALE;
    let _ = writeln!(
        out,
        r##"  <g class="scale-bar"><path d="M{x0:.1},{:.1} V{y:.1} H{x1:.1} V{:.1}" fill="none" stroke="#222" stroke-width="1.5"/><text x="{:.1}" y="{:.1}" font-size="11">{:.0} cm</text></g>"##,
        y - 5.0,
        y - 5.0,
        x1 + 5.0,
        y,
        SCALE_BAR * 100.0
    );
}

/// The snapshots' legend: what the colours mean (the goal region only where there is
/// one; a grasp goal's object is its goal object).
fn legend(film: &Film, out: &mut String) {
    let items = [
        ("rect", GOAL_COLOUR, "goal object"),
        ("circle", GOAL_REGION_COLOUR, "goal region"),
        ("rect", LINK_COLOUR, "arm"),
        ("rect", CONTACT_COLOUR, "link pushing"),
    ];
    let has_region = film.goal_disc().is_some();
    let items = items
        .into_iter()
        .filter(|(_, _, label)| has_region || *label != "goal region");
    let mut x = MARGIN;
    for (shape, colour, label) in items {
        let swatch = match shape {
            "circle" => format!(
                r##"<circle cx="{:.1}" cy="34" r="6" fill="{colour}" fill-opacity="0.15" stroke="{colour}" stroke-dasharray="3 2"/>"##,
                x + 6.0
            ),
            _ => format!(
                r##"<rect x="{x:.1}" y="28" width="12" height="12" fill="{colour}" stroke="#333" stroke-width="0.5"/>"##
            ),
        };
        let _ = writeln!(
            out,
            r##"<g class="legend">{swatch}<text x="{:.1}" y="38" font-size="12">{label}</text></g>"##,
            x + 16.0
        );
        x += 16.0 + 7.0 * label.len() as f64 + 18.0;
    }
}

/// Snapshots at `times` (s), in rows of [`COLUMNS`] under a title and a legend. Each
/// panel has its own frame (`View`), placed by its group's translation.
pub fn snapshots(film: &Film, times: &[f64]) -> String {
    let view = View::of(film);
    let columns = times.len().clamp(1, COLUMNS);
    let rows = times.len().div_ceil(columns).max(1);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{:.0}" height="{:.0}" data-scale="{SCALE}" data-x-top="{}" data-y-left="{}" data-margin="{MARGIN}" font-family="sans-serif" font-size="14">"##,
        view.width * columns as f64,
        HEADER + view.height * rows as f64,
        view.x_top,
        view.y_left
    );
    let _ = writeln!(
        out,
        "<title>{}: snapshots</title>",
        escape(&film.scene.name)
    );
    let _ = writeln!(
        out,
        r##"<text x="{MARGIN}" y="18" font-size="15">{}: the plan seen from above (robot at the bottom)</text>"##,
        escape(&film.scene.name)
    );
    legend(film, &mut out);
    for (n, &t) in times.iter().enumerate() {
        let k = film.step_at(t);
        let frame = film.frame(k);
        let _ = writeln!(
            out,
            r##"<g class="snapshot" data-time="{:.4}" data-step="{k}" transform="translate({:.1},{:.1})">"##,
            frame.time,
            (n % columns) as f64 * view.width,
            HEADER + (n / columns) as f64 * view.height
        );
        panel(film, &view, &frame, k, &mut out);
        let _ = writeln!(
            out,
            r##"  <text x="{MARGIN}" y="16">t = {:.2} s</text>"##,
            frame.time
        );
        let _ = writeln!(out, "</g>");
    }
    out.push_str("</svg>\n");
    out
}

/// Which link touches which object when (Fig. 2, top): one row per link-object pair.
pub fn timeline(film: &Film) -> String {
    let mut pairs: Vec<(usize, usize)> = film.contacts.iter().flatten().copied().collect();
    pairs.sort_unstable();
    pairs.dedup();
    let (label_width, row, px_per_s) =
        (190.0, 22.0, 120.0f64.min(900.0 / film.duration().max(1e-9)));
    let title = format!(
        "Contacts between links and objects over the plan ({:.2} s)",
        film.duration()
    );
    // About 8 px per character at 14 px: the title must fit however short the plan.
    let width =
        (label_width + film.duration() * px_per_s + 30.0).max(8.0 + 8.0 * title.len() as f64);
    let height = 40.0 + row * pairs.len().max(1) as f64 + 30.0;
    let mut out = String::new();
    let _ = writeln!(
        out,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" data-seconds-per-px="{}" font-family="sans-serif" font-size="12">"##,
        1.0 / px_per_s
    );
    let _ = writeln!(out, "<title>{}: contacts</title>", escape(&film.scene.name));
    let _ = writeln!(
        out,
        r##"<text x="4" y="16" font-size="14">{}</text>"##,
        escape(&title)
    );
    let links = &film.scene.robot.chain.links;
    for (r, &(link, object)) in pairs.iter().enumerate() {
        let y = 30.0 + r as f64 * row;
        let name = format!("{} → {}", links[link].name, film.scene.objects[object].name);
        let _ = writeln!(
            out,
            r##"<text x="4" y="{:.1}">{}</text>"##,
            y + 15.0,
            escape(&name)
        );
        let _ = writeln!(
            out,
            r##"<line x1="{label_width}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#ddd"/>"##,
            y + 11.0,
            label_width + film.duration() * px_per_s,
            y + 11.0
        );
        // Contiguous runs of steps with this contact.
        let mut k = 0;
        while k < film.contacts.len() {
            if film.contacts[k].contains(&(link, object)) {
                let start = k;
                while k < film.contacts.len() && film.contacts[k].contains(&(link, object)) {
                    k += 1;
                }
                let _ = writeln!(
                    out,
                    r##"<rect class="contact" data-link="{}" data-object="{}" data-from="{:.4}" data-to="{:.4}" x="{:.1}" y="{:.1}" width="{:.1}" height="14" fill="{}"/>"##,
                    escape(&links[link].name),
                    escape(&film.scene.objects[object].name),
                    start as f64 * film.dt,
                    k as f64 * film.dt,
                    label_width + start as f64 * film.dt * px_per_s,
                    y + 4.0,
                    ((k - start) as f64 * film.dt * px_per_s).max(1.0),
                    object_colour(film, object)
                );
            } else {
                k += 1;
            }
        }
    }
    if pairs.is_empty() {
        let _ = writeln!(out, r##"<text x="4" y="46">no contacts</text>"##);
    }
    let axis_y = 30.0 + row * pairs.len().max(1) as f64 + 8.0;
    let mut s = 0.0;
    while s <= film.duration() + 1e-9 {
        let x = label_width + s * px_per_s;
        let _ = writeln!(
            out,
            r##"<line x1="{x:.1}" y1="{:.1}" x2="{x:.1}" y2="{:.1}" stroke="#888"/><text x="{:.1}" y="{:.1}">{s:.0} s</text>"##,
            axis_y - 4.0,
            axis_y + 2.0,
            x - 6.0,
            axis_y + 16.0
        );
        s += 1.0;
    }
    out.push_str("</svg>\n");
    out
}
