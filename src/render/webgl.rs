//! The animation page's 3D view: the model's own collision shapes as triangle meshes (each
//! in its body's frame: a link's shapes, an object's prism, an obstacle), every frame's body
//! poses, and a small WebGL viewer of the project's own (no library, no network) that draws
//! them with flat shading under an orbit camera, with the objects' names, trails of the
//! objects and the tool, a 20 cm scale bar on the table, and the executed objects as dark
//! ghosts beside the planned ones.

use super::Film;
use nalgebra::{Isometry3, Point3};
use parry3d_f64::shape::SharedShape;
use std::fmt::Write;

/// Sides of a round shape's polygon.
const ROUND: u32 = 24;

/// `shape`'s surface as triangles in its own frame. Shapes without a mesher of their own
/// are drawn as their bounding box.
fn triangles(shape: &SharedShape) -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
    if let Some(s) = shape.as_cuboid() {
        s.to_trimesh()
    } else if let Some(s) = shape.as_cylinder() {
        s.to_trimesh(ROUND)
    } else if let Some(s) = shape.as_capsule() {
        s.to_trimesh(ROUND, ROUND / 2)
    } else if let Some(s) = shape.as_ball() {
        s.to_trimesh(ROUND, ROUND / 2)
    } else if let Some(s) = shape.as_cone() {
        s.to_trimesh(ROUND)
    } else if let Some(s) = shape.as_convex_polyhedron() {
        s.to_trimesh()
    } else if let Some(s) = shape.as_trimesh() {
        (s.vertices().to_vec(), s.indices().to_vec())
    } else if let Some(compound) = shape.as_compound() {
        let mut mesh = Mesh::default();
        for (local, part) in compound.shapes() {
            mesh.add(part, local);
        }
        (mesh.vertices, mesh.indices)
    } else {
        let aabb = shape.compute_local_aabb();
        let (vertices, indices) = parry3d_f64::shape::Cuboid::new(aabb.half_extents()).to_trimesh();
        let centre = aabb.center().coords;
        (vertices.into_iter().map(|v| v + centre).collect(), indices)
    }
}

/// Triangles in one body frame.
#[derive(Default)]
struct Mesh {
    vertices: Vec<Point3<f64>>,
    indices: Vec<[u32; 3]>,
}

impl Mesh {
    /// Adds `shape`, placed at `local` in the body frame.
    fn add(&mut self, shape: &SharedShape, local: &Isometry3<f64>) {
        let (vertices, indices) = triangles(shape);
        let offset = self.vertices.len() as u32;
        self.vertices.extend(vertices.iter().map(|v| local * v));
        self.indices
            .extend(indices.iter().map(|t| t.map(|i| i + offset)));
    }

    fn json(&self) -> String {
        let v: Vec<String> = self
            .vertices
            .iter()
            .flat_map(|p| p.iter().map(|x| format!("{x:.4}")).collect::<Vec<_>>())
            .collect();
        let i: Vec<String> = self.indices.iter().flatten().map(u32::to_string).collect();
        format!("{{\"v\":[{}],\"i\":[{}]}}", v.join(","), i.join(","))
    }
}

/// A pose as `[x, y, z, qx, qy, qz, qw]` (m; the rotation as a unit quaternion).
fn pose(p: &Isometry3<f64>) -> String {
    let (t, q) = (p.translation.vector, p.rotation);
    format!(
        "[{:.4},{:.4},{:.4},{:.5},{:.5},{:.5},{:.5}]",
        t.x, t.y, t.z, q.i, q.j, q.k, q.w
    )
}

/// The 3D view's data (a JavaScript object literal): the meshes, and per frame of
/// `indices` (step indices of `film`) its time and body poses.
pub fn scene_json(film: &Film, indices: &[usize]) -> String {
    let scene = &film.scene;
    let robot = &scene.robot;
    let links: Vec<usize> = robot.solid_links().collect();
    let top = scene.table.top;
    let mesh_of = |geometry: &[&crate::collision::Geometry]| {
        let mut mesh = Mesh::default();
        for g in geometry {
            mesh.add(&g.shape, &g.local);
        }
        mesh.json()
    };
    let link_meshes: Vec<String> = links
        .iter()
        .map(|&l| mesh_of(&robot.chain.links[l].geometry.iter().collect::<Vec<_>>()))
        .collect();
    let object_meshes: Vec<String> = scene
        .objects
        .iter()
        .map(|o| mesh_of(&[&o.geometry]))
        .collect();
    let obstacles: Vec<String> = scene
        .obstacles
        .iter()
        .map(|o| {
            let mut mesh = Mesh::default();
            mesh.add(&o.geometry.shape, &(o.pose * o.geometry.local));
            mesh.json()
        })
        .collect();
    let mut frames = String::from("[");
    for (n, &k) in indices.iter().enumerate() {
        let state = &film.states[k];
        let poses = robot.link_poses(&state.q);
        let tool = robot.tool_pose(&poses).translation.vector;
        let hot: Vec<String> = links
            .iter()
            .enumerate()
            .filter(|(_, &l)| film.link_touching(k, l))
            .map(|(i, _)| i.to_string())
            .collect();
        let objects: Vec<String> = scene
            .objects
            .iter()
            .zip(&state.objects)
            .map(|(o, p)| pose(&o.isometry(p, top)))
            .collect();
        let executed: Vec<String> = film.executed.get(k).map_or(Vec::new(), |ps| {
            scene
                .objects
                .iter()
                .zip(ps)
                .map(|(o, p)| pose(&o.isometry(p, top)))
                .collect()
        });
        let _ = write!(
            frames,
            "{}{{\"t\":{:.3},\"links\":[{}],\"objects\":[{}],\"executed\":[{}],\"hot\":[{}],\"tool\":[{:.4},{:.4},{:.4}]}}",
            if n > 0 { "," } else { "" },
            k as f64 * film.dt,
            links.iter().map(|&l| pose(&poses[l])).collect::<Vec<_>>().join(","),
            objects.join(","),
            executed.join(","),
            hot.join(","),
            tool.x,
            tool.y,
            tool.z
        );
    }
    frames.push(']');
    let t = &scene.table;
    let goal = film.goal_disc().map_or("null".to_string(), |(c, r)| {
        format!("[{:.4},{:.4},{:.4}]", c.x, c.y, r)
    });
    format!(
        "{{\"table\":[{:.4},{:.4},{:.4},{:.4},{:.4}],\"goal\":{goal},\"links\":[{}],\"objects\":[{}],\"obstacles\":[{}],\"frames\":{frames}}}",
        t.x.0,
        t.x.1,
        t.y.0,
        t.y.1,
        top,
        link_meshes.join(","),
        object_meshes.join(","),
        obstacles.join(","),
    )
}

/// The viewer: draws `S3` (from [`scene_json`]) into the canvas `#view3d`, with the
/// objects' colours `colours` and names `names`; `view3d(n)` draws frame `n`. Sets
/// `document.body.dataset.webgl` ("drawn", or why not) and `.painted` (how many of 256
/// sampled pixels are not the background) for a test to read.
pub const VIEWER: &str = r##"
const view3d = (function () {
  const canvas = document.getElementById("view3d");
  const gl = canvas.getContext("webgl", {preserveDrawingBuffer: true, antialias: true});
  const note = document.getElementById("view3d-note");
  if (!gl) {
    document.body.dataset.webgl = "unavailable";
    note.textContent = "WebGL is not available here: the top view below shows the plan.";
    return () => {};
  }
  const shader = (type, text) => {
    const s = gl.createShader(type); gl.shaderSource(s, text); gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  };
  const program = gl.createProgram();
  gl.attachShader(program, shader(gl.VERTEX_SHADER,
    "attribute vec3 p; attribute vec3 n; uniform mat4 mvp; uniform mat4 model; varying vec3 wn;" +
    "void main() { gl_Position = mvp * vec4(p, 1.0); wn = mat3(model) * n; }"));
  gl.attachShader(program, shader(gl.FRAGMENT_SHADER,
    "precision mediump float; uniform vec4 colour; uniform float lit; varying vec3 wn;" +
    "void main() { vec3 l = normalize(vec3(0.35, -0.45, 0.82));" +
    " float d = mix(1.0, 0.35 + 0.65 * abs(dot(normalize(wn), l)), lit);" +
    " gl_FragColor = vec4(colour.rgb * d, colour.a); }"));
  gl.linkProgram(program);
  gl.useProgram(program);
  const at = {p: gl.getAttribLocation(program, "p"), n: gl.getAttribLocation(program, "n")};
  const u = name => gl.getUniformLocation(program, name);
  const uni = {mvp: u("mvp"), model: u("model"), colour: u("colour"), lit: u("lit")};

  // Triangles with a flat normal each (vertices repeated per face).
  function upload(v, idx) {
    const pos = [], nor = [];
    for (let t = 0; t < idx.length; t += 3) {
      const [a, b, c] = [idx[t] * 3, idx[t + 1] * 3, idx[t + 2] * 3];
      const e1 = [v[b] - v[a], v[b + 1] - v[a + 1], v[b + 2] - v[a + 2]];
      const e2 = [v[c] - v[a], v[c + 1] - v[a + 1], v[c + 2] - v[a + 2]];
      const nx = e1[1] * e2[2] - e1[2] * e2[1], ny = e1[2] * e2[0] - e1[0] * e2[2], nz = e1[0] * e2[1] - e1[1] * e2[0];
      for (const i of [a, b, c]) { pos.push(v[i], v[i + 1], v[i + 2]); nor.push(nx, ny, nz); }
    }
    const buffer = data => { const b = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, b); gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(data), gl.STATIC_DRAW); return b; };
    return {pos: buffer(pos), nor: buffer(nor), count: pos.length / 3, mode: gl.TRIANGLES};
  }
  // A polyline through `points` (x, y, z, ...), drawn once and let go.
  function trail(points, colour, alpha) {
    const pos = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, pos);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(points), gl.STREAM_DRAW);
    const nor = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, nor);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(points.length).fill(1), gl.STREAM_DRAW);
    draw({pos: pos, nor: nor, count: points.length / 3, mode: gl.LINE_STRIP}, identity(), colour, alpha, 0);
    gl.deleteBuffer(pos); gl.deleteBuffer(nor);
  }
  // An axis-aligned box from lo to hi, and an upright disc (a flat cylinder).
  function box(lo, hi) {
    const v = [], idx = [];
    for (let i = 0; i < 8; i++) v.push(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]);
    for (const [a, b, c, d] of [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]) idx.push(a, b, c, a, c, d);
    return upload(v, idx);
  }
  function disc(cx, cy, r, z) {
    const v = [cx, cy, z], idx = [];
    for (let i = 0; i <= 48; i++) { const a = 2 * Math.PI * i / 48; v.push(cx + r * Math.cos(a), cy + r * Math.sin(a), z); if (i) idx.push(0, i, i + 1); }
    return upload(v, idx);
  }

  // Column-major 4x4 matrices.
  const mul = (a, b) => { const o = new Float32Array(16); for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) { let s = 0; for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k]; o[c * 4 + r] = s; } return o; };
  const identity = () => new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
  function fromPose([x, y, z, qx, qy, qz, qw]) {
    return new Float32Array([
      1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy + qz * qw), 2 * (qx * qz - qy * qw), 0,
      2 * (qx * qy - qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz + qx * qw), 0,
      2 * (qx * qz + qy * qw), 2 * (qy * qz - qx * qw), 1 - 2 * (qx * qx + qy * qy), 0,
      x, y, z, 1]);
  }
  function perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
    return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0]);
  }
  function lookAt(eye, target, up) {
    const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    const norm = a => { const l = Math.hypot(...a); return a.map(x => x / l); };
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const zc = norm(sub(eye, target)), xc = norm(cross(up, zc)), yc = cross(zc, xc);
    return new Float32Array([xc[0], yc[0], zc[0], 0, xc[1], yc[1], zc[1], 0, xc[2], yc[2], zc[2], 0, -dot(xc, eye), -dot(yc, eye), -dot(zc, eye), 1]);
  }
  const rgb = hex => [1, 3, 5].map(i => parseInt(hex.substr(i, 2), 16) / 255);

  const [x0, x1, y0, y1, top] = S3.table;
  const links = S3.links.map(m => upload(m.v, m.i));
  const objects = S3.objects.map(m => upload(m.v, m.i));
  const obstacles = S3.obstacles.map(m => upload(m.v, m.i));
  const table = box([x0, y0, top - 0.04], [x1, y1, top]);
  const goal = S3.goal && disc(S3.goal[0], S3.goal[1], S3.goal[2], top + 0.001);
  // The scale bar: 20 cm along x at the table's near left corner, and its label.
  const bar = box([x0 + 0.03, y1 - 0.05, top], [x0 + 0.23, y1 - 0.04, top + 0.004]);
  const camera = {az: -2.2, el: 0.55, dist: 2.4, target: [(x0 + x1) / 2, (y0 + y1) / 2, top]};
  const labels = names.map(name => {
    const d = document.createElement("div"); d.className = "label"; d.textContent = name;
    document.getElementById("labels").appendChild(d); return d;
  });
  const scale = document.createElement("div"); scale.className = "label scale"; scale.textContent = "20 cm";
  document.getElementById("labels").appendChild(scale);

  let shown = 0, view = identity();
  function draw(item, model, colour, alpha, lit) {
    gl.uniformMatrix4fv(uni.mvp, false, mul(view, model));
    gl.uniformMatrix4fv(uni.model, false, model);
    gl.uniform4f(uni.colour, colour[0], colour[1], colour[2], alpha);
    gl.uniform1f(uni.lit, lit);
    gl.bindBuffer(gl.ARRAY_BUFFER, item.pos); gl.vertexAttribPointer(at.p, 3, gl.FLOAT, false, 0, 0); gl.enableVertexAttribArray(at.p);
    gl.bindBuffer(gl.ARRAY_BUFFER, item.nor); gl.vertexAttribPointer(at.n, 3, gl.FLOAT, false, 0, 0); gl.enableVertexAttribArray(at.n);
    gl.drawArrays(item.mode, 0, item.count);
  }
  function project(p) {
    const v = [0, 1, 2, 3].map(r => view[r] * p[0] + view[4 + r] * p[1] + view[8 + r] * p[2] + view[12 + r]);
    return [(v[0] / v[3] + 1) / 2 * canvas.width, (1 - v[1] / v[3]) / 2 * canvas.height, v[3] > 0];
  }
  function place(div, p) {
    const [u, v, front] = project(p);
    div.style.left = u + "px"; div.style.top = v + "px"; div.style.display = front ? "" : "none";
  }
  function render(n) {
    shown = n;
    const f = S3.frames[n], c = camera;
    const eye = [c.target[0] + c.dist * Math.cos(c.el) * Math.cos(c.az), c.target[1] + c.dist * Math.cos(c.el) * Math.sin(c.az), c.target[2] + c.dist * Math.sin(c.el)];
    view = mul(perspective(0.7, canvas.width / canvas.height, 0.05, 20), lookAt(eye, c.target, [0, 0, 1]));
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(1, 1, 1, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST); gl.enable(gl.BLEND); gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    draw(table, identity(), rgb("#f2ead8"), 1, 1);
    draw(bar, identity(), [0.1, 0.1, 0.1], 1, 0);
    obstacles.forEach(o => draw(o, identity(), rgb("#8a8f99"), 1, 1));
    objects.forEach((o, i) => draw(o, fromPose(f.objects[i]), rgb(colours[i]), 1, 1));
    links.forEach((l, i) => draw(l, fromPose(f.links[i]), rgb(f.hot.includes(i) ? CONTACT : "#9aa3ad"), 1, 1));
    // Trails: each object's centre and the tool, from the start to this frame.
    const upTo = S3.frames.slice(0, n + 1);
    if (n > 0) {
      objects.forEach((_, i) => trail(upTo.flatMap(g => [g.objects[i][0], g.objects[i][1], top + 0.002]), rgb(colours[i]), 1));
      trail(upTo.flatMap(g => g.tool), rgb(CONTACT), 0.8);
    }
    // See-through last: the goal region and where the execution took the objects.
    gl.depthMask(false);
    if (goal) draw(goal, identity(), rgb(GOAL_REGION), 0.3, 0);
    f.executed.forEach((p, i) => draw(objects[i], fromPose(p), [0.1, 0.1, 0.1], 0.35, 1));
    gl.depthMask(true);
    labels.forEach((d, i) => place(d, [f.objects[i][0], f.objects[i][1], f.objects[i][2] + 0.02]));
    place(scale, [x0 + 0.13, y1 - 0.06, top]);
    if (!document.body.dataset.webgl) {
      const px = new Uint8Array(4); let painted = 0;
      for (let i = 0; i < 16; i++) for (let j = 0; j < 16; j++) {
        gl.readPixels(Math.floor((i + 0.5) * canvas.width / 16), Math.floor((j + 0.5) * canvas.height / 16), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
        if (px[0] < 250 || px[1] < 250 || px[2] < 250) painted++;
      }
      document.body.dataset.painted = painted;
      const error = gl.getError();
      document.body.dataset.webgl = error === gl.NO_ERROR ? "drawn" : "error " + error;
    }
  }
  // Drag to turn the camera about the table, the wheel to come closer.
  let drag = null;
  canvas.addEventListener("mousedown", e => { drag = [e.clientX, e.clientY]; });
  window.addEventListener("mouseup", () => { drag = null; });
  window.addEventListener("mousemove", e => {
    if (!drag) return;
    camera.az -= (e.clientX - drag[0]) * 0.01;
    camera.el = Math.min(1.5, Math.max(0.05, camera.el + (e.clientY - drag[1]) * 0.01));
    drag = [e.clientX, e.clientY]; render(shown);
  });
  canvas.addEventListener("wheel", e => { e.preventDefault(); camera.dist = Math.min(8, Math.max(0.4, camera.dist * Math.exp(e.deltaY * 0.001))); render(shown); });
  return render;
})();
"##;
