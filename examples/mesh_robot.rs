//! Writes `robots/wam7_mesh.urdf`: the WAM of `robots/wam7.urdf` with every collision
//! primitive replaced by a tessellated mesh, alternately Wavefront OBJ (metres) and
//! COLLADA (millimetres, `<unit meter="0.001">`, Y up), in `robots/meshes/wam7/`. The
//! shipped mesh robot of the tests and of `BENCHMARKS.md` ("Mesh robots") is this
//! program's output:
//!
//! ```sh
//! cargo run --release --example mesh_robot
//! ```

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

/// Segments around a round primitive's axis, and rings from pole to pole of a sphere.
const SEGMENTS: usize = 32;
const RINGS: usize = 16;

/// A triangle mesh, vertices in metres.
struct Mesh {
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[usize; 3]>,
}

impl Mesh {
    /// Rings of points around z (each `(z, radius)`, bottom to top), closed by a vertex
    /// at each pole when the first and last radius are zero.
    fn lathe(profile: &[(f64, f64)]) -> Mesh {
        let mut vertices = Vec::new();
        let mut rings = Vec::new();
        for &(z, r) in profile {
            if r == 0.0 {
                rings.push(vec![vertices.len()]);
                vertices.push([0.0, 0.0, z]);
            } else {
                rings.push((vertices.len()..vertices.len() + SEGMENTS).collect());
                for s in 0..SEGMENTS {
                    let a = 2.0 * PI * s as f64 / SEGMENTS as f64;
                    vertices.push([r * a.cos(), r * a.sin(), z]);
                }
            }
        }
        let mut triangles = Vec::new();
        for pair in rings.windows(2) {
            let (lo, hi) = (&pair[0], &pair[1]);
            for s in 0..SEGMENTS {
                let at = |ring: &Vec<usize>, i: usize| ring[i % ring.len()];
                let (a, b) = (at(lo, s), at(lo, s + 1));
                let (c, d) = (at(hi, s), at(hi, s + 1));
                if a != b {
                    triangles.push([a, b, d]);
                }
                if c != d {
                    triangles.push([a, d, c]);
                }
            }
        }
        Mesh {
            vertices,
            triangles,
        }
    }

    fn sphere(radius: f64) -> Mesh {
        let profile: Vec<(f64, f64)> = (0..=RINGS)
            .map(|i| {
                let polar = PI * (1.0 - i as f64 / RINGS as f64);
                let r = if i == 0 || i == RINGS {
                    0.0
                } else {
                    radius * polar.sin()
                };
                (radius * polar.cos(), r)
            })
            .collect();
        Mesh::lathe(&profile)
    }

    fn cylinder(radius: f64, length: f64) -> Mesh {
        let h = length / 2.0;
        Mesh::lathe(&[(-h, 0.0), (-h, radius), (h, radius), (h, 0.0)])
    }

    /// `length` is the inner segment's, as in URDF.
    fn capsule(radius: f64, length: f64) -> Mesh {
        let h = length / 2.0;
        let cap = |i: usize| PI / 2.0 * i as f64 / (RINGS / 2) as f64;
        let mut profile = Vec::new();
        for i in (0..=RINGS / 2).rev() {
            let r = if i == RINGS / 2 {
                0.0
            } else {
                radius * cap(i).cos()
            };
            profile.push((-h - radius * cap(i).sin(), r));
        }
        for i in 0..=RINGS / 2 {
            let r = if i == RINGS / 2 {
                0.0
            } else {
                radius * cap(i).cos()
            };
            profile.push((h + radius * cap(i).sin(), r));
        }
        Mesh::lathe(&profile)
    }

    fn cuboid(size: [f64; 3]) -> Mesh {
        let h = size.map(|s| s / 2.0);
        let vertices = (0..8)
            .map(|i| {
                [
                    if i & 1 == 0 { -h[0] } else { h[0] },
                    if i & 2 == 0 { -h[1] } else { h[1] },
                    if i & 4 == 0 { -h[2] } else { h[2] },
                ]
            })
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        let triangles = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        Mesh {
            vertices,
            triangles,
        }
    }

    fn obj(&self, name: &str) -> String {
        let mut out =
            format!("# {name}: tessellated by examples/mesh_robot.rs (metres)\no {name}\n");
        for v in &self.vertices {
            writeln!(out, "v {:.6} {:.6} {:.6}", v[0], v[1], v[2]).unwrap();
        }
        for t in &self.triangles {
            writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1).unwrap();
        }
        out
    }

    /// COLLADA in millimetres with y up: a vertex (x, y, z) of the robot's frame is
    /// written as (x, z, -y) in mm, which a reader that honours `<unit>` and `<up_axis>`
    /// turns back.
    fn dae(&self, name: &str) -> String {
        let positions: Vec<String> = self
            .vertices
            .iter()
            .map(|v| {
                format!(
                    "{:.4} {:.4} {:.4}",
                    v[0] * 1000.0,
                    v[2] * 1000.0,
                    -v[1] * 1000.0
                )
            })
            .collect();
        let indices: Vec<String> = self
            .triangles
            .iter()
            .map(|t| format!("{} {} {}", t[0], t[1], t[2]))
            .collect();
        let n = self.vertices.len();
        format!(
            r##"<?xml version="1.0" encoding="utf-8"?>
<!-- {name}: tessellated by examples/mesh_robot.rs (millimetres, y up) -->
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="millimeter" meter="0.001"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="{name}-mesh" name="{name}">
      <mesh>
        <source id="{name}-positions">
          <float_array id="{name}-positions-array" count="{count}">{positions}</float_array>
          <technique_common>
            <accessor source="#{name}-positions-array" count="{n}" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="{name}-vertices"><input semantic="POSITION" source="#{name}-positions"/></vertices>
        <triangles count="{triangles}"><input semantic="VERTEX" source="#{name}-vertices" offset="0"/><p>{indices}</p></triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene"><node id="{name}"><instance_geometry url="#{name}-mesh"/></node></visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
"##,
            count = 3 * n,
            positions = positions.join(" "),
            triangles = self.triangles.len(),
            indices = indices.join(" "),
        )
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("robots");
    let text = std::fs::read_to_string(root.join("wam7.urdf"))?;
    let robot = urdf_rs::read_from_string(&text)?;
    std::fs::create_dir_all(root.join("meshes/wam7"))?;
    // The URDF's `<geometry>` elements in document order are its links' collisions in order.
    let mut out = String::new();
    let mut rest = text.as_str();
    let collisions = robot
        .links
        .iter()
        .flat_map(|l| l.collision.iter().map(move |c| (l.name.as_str(), c)));
    for (i, (link, collision)) in collisions.enumerate() {
        let mesh = match &collision.geometry {
            urdf_rs::Geometry::Box { size } => Mesh::cuboid(**size),
            urdf_rs::Geometry::Cylinder { radius, length } => Mesh::cylinder(*radius, *length),
            urdf_rs::Geometry::Capsule { radius, length } => Mesh::capsule(*radius, *length),
            urdf_rs::Geometry::Sphere { radius } => Mesh::sphere(*radius),
            urdf_rs::Geometry::Mesh { .. } => {
                return Err(format!("{link} is a mesh already").into())
            }
        };
        let file = if i % 2 == 0 {
            let file = format!("meshes/wam7/{link}.obj");
            std::fs::write(root.join(&file), mesh.obj(link))?;
            file
        } else {
            let file = format!("meshes/wam7/{link}.dae");
            std::fs::write(root.join(&file), mesh.dae(link))?;
            file
        };
        let start = rest
            .find("<geometry>")
            .ok_or("fewer <geometry> than collisions")?;
        let end = rest[start..]
            .find("</geometry>")
            .ok_or("unclosed <geometry>")?
            + start;
        out.push_str(&rest[..start]);
        write!(out, "<geometry><mesh filename=\"{file}\"/>")?;
        rest = &rest[end..];
        println!("{file}: {} vertices", mesh.vertices.len());
    }
    out.push_str(rest);
    let out = out.replacen(
        "<robot",
        "<!-- robots/wam7.urdf with tessellated meshes: written by examples/mesh_robot.rs -->\n<robot",
        1,
    );
    std::fs::write(root.join("wam7_mesh.urdf"), out)?;
    println!("robots/wam7_mesh.urdf");
    Ok(())
}
