//! From a scene file to a validated [`Scene`]: every number is checked (finite, in range),
//! every reference resolved, and every error names the file and the field.

use super::file::{
    GoalSpec, GraspSpec, ObjectSpec, PhysicsModel, PhysicsSpec, PlannerSpec, PressureSpec,
    RobotSpec, SceneFile, ShapeSpec, TableSpec,
};
use super::Clearances;
use super::{
    default_goal_margin, AllowedCollisions, Goal, Grasp, MovableObject, Obstacle, Scene, Table,
};
use crate::collision::{Geometry, Primitive};
use crate::error::{Error, Result};
use crate::input::name_list;
use crate::limits::MAX_EXTENT;
use crate::math::{isometry_from_xyz_rpy, Pose2};
use crate::physics::limit_surface::GRAVITY;
use crate::physics::{Footprint, LimitSurface, LoadedSupport};
use crate::robot::mesh::load_convex_mesh;
use crate::robot::planar_hand::planar_hand_chain;
use crate::robot::projection::ProjectionSettings;
use crate::robot::srdf::Srdf;
use crate::robot::urdf::{check_dimensions, load_urdf_chain};
use crate::robot::wgr::Wgr;
use crate::robot::{PushingPlane, Robot, RobotKind};
use crate::state::State;
use nalgebra::{DVector, Isometry3, Point3, UnitQuaternion, Vector2, Vector3};
use std::path::{Path, PathBuf};

impl Scene {
    /// Loads and validates the scene file at `path`.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene> {
        let path = path.as_ref();
        let text = crate::input::read_text(path, crate::input::MAX_SCENE_BYTES)
            .map_err(|message| Error::io(path, message))?;
        Scene::from_yaml(&text, path)
    }

    /// Loads the scene file at `path` like [`Scene::load`], except that a start
    /// configuration off its pushing plane, outside the joint limits or in collision is
    /// reported beside the scene instead of refusing it (its `start.q` is then
    /// `start_joints` as written): for inspecting the robot while choosing start joints.
    pub fn load_any_start(path: impl AsRef<Path>) -> Result<(Scene, Option<String>)> {
        let path = path.as_ref();
        let text = crate::input::read_text(path, crate::input::MAX_SCENE_BYTES)
            .map_err(|message| Error::io(path, message))?;
        let spec = parse(&text, path)?;
        let loader = Loader {
            file: path,
            start: StartCheck::Report(Default::default()),
        };
        let scene = loader.scene(spec)?;
        let problem = match loader.start {
            StartCheck::Report(problem) => problem.into_inner(),
            StartCheck::Require => None,
        };
        Ok((scene, problem))
    }

    /// Parses scene YAML. `source` names the scene in errors, and relative file
    /// references (URDF, meshes) are resolved against its folder.
    pub fn from_yaml(text: &str, source: &Path) -> Result<Scene> {
        if let Some(line) = too_deep(text) {
            return Err(Error::Parse {
                file: source.to_path_buf(),
                field: String::new(),
                message: format!(
                    "line {line}: nested more than {MAX_NESTING} levels deep (a scene needs a few)"
                ),
            });
        }
        let spec = parse(text, source)?;
        Loader {
            file: source,
            start: StartCheck::Require,
        }
        .scene(spec)
    }
}

/// The scene file's syntax: YAML into [`SceneFile`], errors naming the field, the line
/// and the column.
fn parse(text: &str, source: &Path) -> Result<SceneFile> {
    let options = serde_saphyr::options! { with_snippet: false };
    let mut field = String::new();
    serde_saphyr::with_deserializer_from_str_with_options(text, options, |deserializer| {
        serde_path_to_error::deserialize(deserializer).map_err(|e| {
            field = e.path().to_string();
            e.into_inner()
        })
    })
    .map_err(|e| {
        // "error: line L column C: what" -> "line L column C: what".
        let message = e.to_string();
        let message = message.strip_prefix("error: ").unwrap_or(&message);
        Error::Parse {
            file: source.to_path_buf(),
            field: if field == "." { String::new() } else { field },
            message: crate::input::shorten_quoted(message),
        }
    })
}

/// Most movable objects in a scene.
pub const MAX_OBJECTS: usize = 64;
/// Shortest edge of a polygon footprint (m).
const MIN_EDGE: f64 = 1e-6;
/// Heaviest object (kg).
pub const MAX_MASS: f64 = 1000.0;
/// Largest friction coefficient (`mu_g`, `mu_c`).
pub const MAX_FRICTION: f64 = 10.0;
/// Most control samples per extension (`planner.k`).
pub const MAX_K: u32 = crate::limits::K.most as u32;
/// Shortest and longest propagation step (s): shorter steps make paths of millions of
/// steps, longer ones let a link pass through an object within one step.
pub const MIN_STEP: f64 = 1e-4;
/// Longest propagation step (s).
pub const MAX_STEP: f64 = 0.1;
/// Farthest the tool may move in one propagation step (m): `planner.max_ee_speed x
/// planner.step`, the longest step at the default speed.
pub const MAX_STEP_TRAVEL: f64 = 0.05;
/// Most the tool may turn, or the null space move, in one propagation step (rad):
/// `planner.max_ee_turn_rate` or `planner.max_nullspace_speed` times `planner.step`, the
/// longest step at the default rates.
pub const MAX_STEP_TURN: f64 = 0.1;
/// Most propagation steps in one control (`planner.max_duration / planner.step`).
pub const MAX_CONTROL_STEPS: usize = 10_000;

/// Deepest nesting of flow collections (`[`, `{`) a scene file may have.
const MAX_NESTING: usize = 32;

/// The line where the flow collections of `text` nest deeper than [`MAX_NESTING`], if
/// they do. The YAML parser's time grows with the square of the depth; a scene needs
/// four or five levels. Brackets inside quotes and comments count too: no real scene
/// has 32 of them open at once.
fn too_deep(text: &str) -> Option<usize> {
    let mut depth = 0usize;
    let mut line = 1;
    for c in text.chars() {
        match c {
            '[' | '{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Some(line);
                }
            }
            ']' | '}' => depth = depth.saturating_sub(1),
            '\n' => line += 1,
            _ => {}
        }
    }
    None
}

struct Loader<'a> {
    file: &'a Path,
    start: StartCheck,
}

/// What a start configuration that is not on its plane, within its limits and free of
/// collisions does to the scene: refuses it, or is reported beside it.
enum StartCheck {
    Require,
    Report(std::cell::RefCell<Option<String>>),
}

impl Loader<'_> {
    /// `problem` with the start configuration: an error, or noted when only reported.
    fn start_problem(&self, problem: Error) -> Result<()> {
        match &self.start {
            StartCheck::Require => Err(problem),
            StartCheck::Report(noted) => {
                noted.borrow_mut().get_or_insert(problem.to_string());
                Ok(())
            }
        }
    }

    fn invalid(&self, field: impl Into<String>, message: impl Into<String>) -> Error {
        Error::invalid(self.file, field, message)
    }

    /// Coordinates, angles and joint values: finite, and within [`MAX_EXTENT`] of zero.
    fn finite(&self, field: &str, values: &[f64]) -> Result<()> {
        let plausible = |v: &f64| v.is_finite() && v.abs() <= MAX_EXTENT;
        let message =
            |v: f64| format!("must be a finite number within +-{MAX_EXTENT} (m or rad), got {v}");
        match values.iter().position(|v| !plausible(v)) {
            None => Ok(()),
            Some(i) if values.len() == 1 => Err(self.invalid(field, message(values[i]))),
            Some(i) => Err(self.invalid(format!("{field}[{i}]"), message(values[i]))),
        }
    }

    /// A length (m): positive, and at most [`MAX_EXTENT`].
    fn length(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value > 0.0 && value <= MAX_EXTENT {
            return Ok(());
        }
        Err(self.invalid(
            field,
            format!("must be positive and at most {MAX_EXTENT} m, got {value:?}"),
        ))
    }

    fn positive(&self, field: &str, value: f64) -> Result<()> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(self.invalid(field, format!("must be positive and finite, got {value:?}")))
        }
    }

    /// `value` within `[low, high]`; `what` says why the bound exists.
    fn within(&self, field: &str, value: f64, low: f64, high: f64, what: &str) -> Result<()> {
        if value.is_finite() && (low..=high).contains(&value) {
            Ok(())
        } else {
            Err(self.invalid(
                field,
                format!("must be in [{low}, {high}] ({what}), got {value:?}"),
            ))
        }
    }

    /// Every value of `q` within its joint's limits, or an error naming `field[i]`;
    /// `note` follows the value in the message.
    fn within_joint_limits(
        &self,
        field: &str,
        note: &str,
        robot: &Robot,
        q: &DVector<f64>,
    ) -> Result<()> {
        match robot.chain.within_limits(q) {
            Ok(()) => Ok(()),
            Err(i) => {
                let j = robot.chain.dof_joint(i);
                Err(self.invalid(
                    format!("{field}[{i}]"),
                    format!(
                        "{:.4}{note} is outside joint '{}' limits [{}, {}]",
                        q[i], j.name, j.lower, j.upper
                    ),
                ))
            }
        }
    }

    /// A name: not empty, no control characters.
    fn name(&self, field: &str, name: &str) -> Result<()> {
        if name.trim().is_empty() || name.chars().any(char::is_control) {
            return Err(self.invalid(
                field,
                format!("{name:?} is not a name (empty, or with control characters)"),
            ));
        }
        Ok(())
    }

    fn relative(&self, path: &Path) -> PathBuf {
        self.file.parent().unwrap_or(Path::new(".")).join(path)
    }

    fn scene(&self, spec: SceneFile) -> Result<Scene> {
        let table = self.table(&spec.table)?;
        let obstacles = spec
            .obstacles
            .iter()
            .enumerate()
            .map(|(i, o)| {
                let field = format!("obstacles[{i}]");
                self.name(&format!("{field}.name"), &o.name)?;
                self.finite(&format!("{field}.pose.xyz"), &o.pose.xyz)?;
                self.finite(&format!("{field}.pose.rpy"), &o.pose.rpy)?;
                let (primitive, _) = self.shape(&format!("{field}.shape"), &o.shape, true)?;
                let geometry =
                    self.geometry(&format!("{field}.shape"), &primitive, Isometry3::identity())?;
                Ok(Obstacle {
                    name: o.name.clone(),
                    pose: isometry_from_xyz_rpy(o.pose.xyz, o.pose.rpy),
                    geometry,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        if spec.objects.len() > MAX_OBJECTS {
            return Err(self.invalid(
                "objects",
                format!(
                    "{} objects; a scene has at most {MAX_OBJECTS}",
                    spec.objects.len()
                ),
            ));
        }
        let mut objects = Vec::new();
        let mut poses = Vec::new();
        for (i, o) in spec.objects.iter().enumerate() {
            self.name(&format!("objects[{i}].name"), &o.name)?;
            if spec.objects[..i].iter().any(|p| p.name == o.name) {
                return Err(self.invalid(
                    format!("objects[{i}].name"),
                    format!("'{}' is used twice", o.name),
                ));
            }
            let (object, pose) = self.object(&format!("objects[{i}]"), o, &table)?;
            objects.push(object);
            poses.push(pose);
        }
        let planner = self.planner(&spec.planner)?;
        let physics = self.physics(&spec.physics)?;
        for (field, value) in [
            (
                "trajectory.max_joint_acceleration",
                spec.trajectory.max_joint_acceleration,
            ),
            (
                "trajectory.max_object_speed",
                spec.trajectory.max_object_speed,
            ),
        ] {
            self.positive(field, value)?;
        }
        let settings = ProjectionSettings {
            max_joint_speed: physics.max_joint_speed,
            height_tolerance: physics.plane_tolerance,
            tilt_tolerance: physics.tilt_tolerance,
            ..ProjectionSettings::default()
        };
        let (mut robot, q) = self.robot(&spec.robot, &table, &planner, &settings)?;
        let allowed = self.allowed_collisions(&spec, &mut robot, &obstacles)?;
        let goal = match &spec.goal.grasp {
            Some(name) => self.grasp_goal(&spec.goal, name, &objects, &table, &robot)?,
            None => self.goal(&spec.goal, &objects, &table, robot.dof())?,
        };
        if let Goal::Configuration { q, .. } = &goal {
            self.within_joint_limits("goal.configuration", "", &robot, q)?;
        }
        let name = spec.name.clone().unwrap_or_else(|| {
            self.file
                .file_stem()
                .map_or("scene".into(), |s| s.to_string_lossy().into_owned())
        });
        let mut scene = Scene {
            name,
            source: self.file.to_path_buf(),
            robot,
            table,
            obstacles,
            objects,
            goal,
            planner,
            physics,
            trajectory: spec.trajectory.clone(),
            start: State { q, objects: poses },
            clearances: Clearances::default(),
            allowed,
        };
        scene.clearances = Clearances::at_start(&scene);
        if let Err(rule) = crate::validity::check_state(&scene, &scene.start) {
            self.start_problem(Error::InvalidStart {
                file: self.file.to_path_buf(),
                rule,
            })?;
        }
        Ok(scene)
    }

    /// The SRDF `robot.srdf` names (relative to the scene file), else the one beside the
    /// URDF (its path with `.srdf`) if there is one; with its path.
    fn srdf(&self, named: Option<&Path>, urdf_path: &Path) -> Result<Option<(Srdf, PathBuf)>> {
        let path = match named {
            Some(named) => {
                let path = self.relative(named);
                if let Some(why) = crate::input::not_a_regular_file(&path) {
                    return Err(
                        self.invalid("robot.srdf", format!("file {}: {why}", path.display()))
                    );
                }
                path
            }
            None => {
                let beside = urdf_path.with_extension("srdf");
                if !beside.is_file() {
                    return Ok(None);
                }
                beside
            }
        };
        Ok(Some((Srdf::read(&path)?, path)))
    }

    /// Resolves `allowed_collisions`: each pair names a robot link and the table, an
    /// obstacle or another link. Allowed link pairs leave the robot's self-collision pairs.
    fn allowed_collisions(
        &self,
        spec: &SceneFile,
        robot: &mut Robot,
        obstacles: &[Obstacle],
    ) -> Result<AllowedCollisions> {
        #[derive(Clone, Copy, PartialEq)]
        enum Named {
            Link(usize),
            Table,
            Obstacle(usize),
        }
        let links = &robot.chain.links;
        let mut allowed = AllowedCollisions::default();
        let mut link_pairs = Vec::new();
        for (i, pair) in spec.allowed_collisions.iter().enumerate() {
            let mut named = [Named::Table; 2];
            for (k, name) in pair.iter().enumerate() {
                let field = format!("allowed_collisions[{i}][{k}]");
                let link = links.iter().position(|l| &l.name == name);
                let obstacle = obstacles.iter().position(|o| &o.name == name);
                named[k] = match (link, obstacle, name == "table") {
                    (Some(l), None, false) => Named::Link(l),
                    (None, Some(o), false) => Named::Obstacle(o),
                    (None, None, true) => Named::Table,
                    (None, None, false) => {
                        let message = if spec.objects.iter().any(|o| &o.name == name) {
                            format!("'{name}' is a movable object: the arm pushes objects, it cannot pass through them")
                        } else {
                            format!(
                                "no link or obstacle named '{name}'; the links are {}; the obstacles are {}; or 'table'",
                                name_list(links.iter().map(|l| l.name.as_str())),
                                name_list(obstacles.iter().map(|o| o.name.as_str()))
                            )
                        };
                        return Err(self.invalid(field, message));
                    }
                    _ => {
                        return Err(self.invalid(
                            field,
                            format!("'{name}' names more than one of a link, an obstacle and the table; rename the obstacle"),
                        ))
                    }
                };
            }
            match named {
                [Named::Link(a), Named::Link(b)] => link_pairs.push((a, b)),
                [Named::Link(l), Named::Table] | [Named::Table, Named::Link(l)] => {
                    allowed.table.push(l)
                }
                [Named::Link(l), Named::Obstacle(o)] | [Named::Obstacle(o), Named::Link(l)] => {
                    allowed.obstacles.push((l, o))
                }
                _ => {
                    return Err(self.invalid(
                        format!("allowed_collisions[{i}]"),
                        format!(
                            "{:?}: one of a pair must be a link of the robot (the static world never moves into itself)",
                            pair
                        ),
                    ))
                }
            }
        }
        robot.skip_self_collisions(&link_pairs);
        Ok(allowed)
    }

    fn table(&self, t: &TableSpec) -> Result<Table> {
        self.finite("table.height", &[t.height])?;
        self.finite("table.x", &t.x)?;
        self.finite("table.y", &t.y)?;
        self.length("table.thickness", t.thickness)?;
        for (field, r) in [("table.x", t.x), ("table.y", t.y)] {
            if r[0] >= r[1] {
                return Err(self.invalid(
                    field,
                    format!("must be [min, max] with min < max, got {r:?}"),
                ));
            }
        }
        let size = Vector3::new(t.x[1] - t.x[0], t.y[1] - t.y[0], t.thickness);
        let centre = Isometry3::translation(
            (t.x[0] + t.x[1]) / 2.0,
            (t.y[0] + t.y[1]) / 2.0,
            t.height - t.thickness / 2.0,
        );
        Ok(Table {
            top: t.height,
            x: (t.x[0], t.x[1]),
            y: (t.y[0], t.y[1]),
            geometry: self.geometry("table", &Primitive::Box { size }, centre)?,
        })
    }

    fn geometry(
        &self,
        field: &str,
        primitive: &Primitive,
        local: Isometry3<f64>,
    ) -> Result<Geometry> {
        Geometry::new(primitive, local)
            .ok_or_else(|| self.invalid(field, "the shape is flat (no volume)"))
    }

    /// The primitive of a shape and, for prisms, its footprint and height.
    /// Prisms are placed with their base at the frame origin when `centred` is false.
    fn shape(
        &self,
        field: &str,
        shape: &ShapeSpec,
        centred: bool,
    ) -> Result<(Primitive, Option<(Footprint, f64)>)> {
        let out = match shape {
            ShapeSpec::Box { size } => {
                let [x, y, z] = *size;
                let footprint = Footprint::Polygon {
                    vertices: vec![
                        Vector2::new(-x / 2.0, -y / 2.0),
                        Vector2::new(x / 2.0, -y / 2.0),
                        Vector2::new(x / 2.0, y / 2.0),
                        Vector2::new(-x / 2.0, y / 2.0),
                    ],
                };
                (
                    Primitive::Box {
                        size: Vector3::from(*size),
                    },
                    Some((footprint, z)),
                )
            }
            ShapeSpec::Cylinder { radius, height } => (
                Primitive::Cylinder {
                    radius: *radius,
                    length: *height,
                },
                Some((Footprint::Circle { radius: *radius }, *height)),
            ),
            ShapeSpec::Polygon { vertices, height } => {
                let footprint = self.polygon(&format!("{field}.vertices"), vertices)?;
                let Footprint::Polygon { vertices: v } = &footprint else {
                    unreachable!()
                };
                let z0 = if centred { -height / 2.0 } else { 0.0 };
                let points = v
                    .iter()
                    .flat_map(|p| {
                        [
                            Point3::new(p.x, p.y, z0),
                            Point3::new(p.x, p.y, z0 + height),
                        ]
                    })
                    .collect();
                (Primitive::ConvexHull { points }, Some((footprint, *height)))
            }
            ShapeSpec::Mesh { file, scale } => {
                self.finite(&format!("{field}.scale"), scale)?;
                if !self.relative(file).is_file() {
                    return Err(self.invalid(
                        format!("{field}.file"),
                        format!("mesh {} not found", self.relative(file).display()),
                    ));
                }
                (load_convex_mesh(&self.relative(file), *scale)?, None)
            }
        };
        check_dimensions(&out.0).map_err(|m| self.invalid(field, m))?;
        if let Some((_, h)) = &out.1 {
            self.length(&format!("{field}.height"), *h)?;
        }
        Ok(out)
    }

    /// A convex polygon footprint, made counter-clockwise, whose centroid is the origin.
    fn polygon(&self, field: &str, vertices: &[[f64; 2]]) -> Result<Footprint> {
        if vertices.len() < 3 {
            return Err(self.invalid(field, "a polygon needs at least 3 vertices"));
        }
        for (i, v) in vertices.iter().enumerate() {
            self.finite(&format!("{field}[{i}]"), v)?;
        }
        let mut v: Vec<Vector2<f64>> = vertices.iter().map(|p| Vector2::new(p[0], p[1])).collect();
        let n = v.len();
        // An edge needs a length to have an outward normal (the footprint queries use them).
        if let Some(i) = (0..n).find(|&i| (v[(i + 1) % n] - v[i]).norm() < MIN_EDGE) {
            return Err(self.invalid(
                field,
                format!(
                    "vertices {i} and {} coincide (an edge needs at least {MIN_EDGE} m)",
                    (i + 1) % n
                ),
            ));
        }
        let turn = |a: Vector2<f64>, b: Vector2<f64>, c: Vector2<f64>| (b - a).perp(&(c - b));
        let turns: Vec<f64> = (0..n)
            .map(|i| turn(v[i], v[(i + 1) % n], v[(i + 2) % n]))
            .collect();
        if turns.iter().all(|t| *t <= 0.0) {
            v.reverse();
        } else if !turns.iter().all(|t| *t >= 0.0) {
            return Err(self.invalid(field, "the polygon is not convex"));
        }
        let footprint = Footprint::Polygon { vertices: v };
        if footprint.area() <= 1e-8 {
            return Err(self.invalid(field, "the polygon has no area"));
        }
        let c = footprint.centroid();
        if c.norm() > 1e-3 {
            return Err(self.invalid(
                field,
                format!(
                    "the footprint's centroid is at ({:.4}, {:.4}); vertices must be given about the centroid (the object's pose is its centre of friction)",
                    c.x, c.y
                ),
            ));
        }
        Ok(footprint)
    }

    fn object(&self, field: &str, o: &ObjectSpec, table: &Table) -> Result<(MovableObject, Pose2)> {
        let (primitive, prism) = self.shape(&format!("{field}.shape"), &o.shape, false)?;
        let Some((footprint, height)) = prism else {
            return Err(self.invalid(
                format!("{field}.shape"),
                "a movable object must be a box, cylinder or polygon prism",
            ));
        };
        let local = match o.shape {
            ShapeSpec::Polygon { .. } => Isometry3::identity(),
            _ => Isometry3::translation(0.0, 0.0, height / 2.0),
        };
        let geometry = self.geometry(&format!("{field}.shape"), &primitive, local)?;
        self.finite(&format!("{field}.pose"), &o.pose)?;
        let pose = Pose2::new(o.pose[0], o.pose[1], crate::math::wrap_angle(o.pose[2]));
        if !table.contains(pose.translation()) {
            return Err(self.invalid(
                format!("{field}.pose"),
                format!("centre ({}, {}) is off the table", pose.x, pose.y),
            ));
        }
        if !table.holds(&footprint, &pose) {
            return Err(self.invalid(
                format!("{field}.pose"),
                format!(
                    "the footprint at ({}, {}) reaches past the table's edge",
                    pose.x, pose.y
                ),
            ));
        }
        self.positive(&format!("{field}.mass"), o.mass)?;
        self.positive(&format!("{field}.mu_g"), o.mu_g)?;
        self.positive(&format!("{field}.mu_c"), o.mu_c)?;
        self.within(
            &format!("{field}.mass"),
            o.mass,
            0.0,
            MAX_MASS,
            "kg, a tabletop object",
        )?;
        for (key, mu) in [("mu_g", o.mu_g), ("mu_c", o.mu_c)] {
            self.within(
                &format!("{field}.{key}"),
                mu,
                0.0,
                MAX_FRICTION,
                "a friction coefficient",
            )?;
        }
        let c = match o.pressure {
            PressureSpec::Uniform => footprint.characteristic_length(),
            PressureSpec::CharacteristicLength { c } => {
                self.positive(&format!("{field}.pressure.c"), c)?;
                c
            }
        };
        let bounding_radius = match &footprint {
            Footprint::Circle { radius } => *radius,
            Footprint::Polygon { vertices } => {
                vertices.iter().map(|v| v.norm()).fold(0.0, f64::max)
            }
        };
        let object = MovableObject {
            name: o.name.clone(),
            footprint: footprint.clone(),
            height,
            geometry,
            bounding_radius,
            mass: o.mass,
            mu_g: o.mu_g,
            mu_c: o.mu_c,
            limit_surface: LimitSurface {
                c,
                f_max: o.mu_g * o.mass * GRAVITY,
                centre: Vector2::zeros(),
            },
            support: LoadedSupport::new(&footprint),
            grasps: o
                .grasps
                .iter()
                .enumerate()
                .map(|(g, spec)| self.grasp(&format!("{field}.grasps[{g}]"), spec))
                .collect::<Result<_>>()?,
        };
        Ok((object, pose))
    }

    /// A grasp region: finite poses, each bound [min, max] with min <= max, angles
    /// within [-pi, pi].
    fn grasp(&self, field: &str, g: &GraspSpec) -> Result<Grasp> {
        for (name, pose) in [("frame", &g.frame), ("end_effector", &g.end_effector)] {
            self.finite(&format!("{field}.{name}.xyz"), &pose.xyz)?;
            self.finite(&format!("{field}.{name}.rpy"), &pose.rpy)?;
        }
        let b = &g.bounds;
        let named = [
            ("x", b.x),
            ("y", b.y),
            ("z", b.z),
            ("roll", b.roll),
            ("pitch", b.pitch),
            ("yaw", b.yaw),
        ];
        let mut bounds = [(0.0, 0.0); 6];
        for (k, (name, [lo, hi])) in named.into_iter().enumerate() {
            let at = format!("{field}.bounds.{name}");
            self.finite(&at, &[lo, hi])?;
            if lo > hi {
                return Err(self.invalid(
                    at,
                    format!("must be [min, max] with min <= max, got [{lo}, {hi}]"),
                ));
            }
            let pi = std::f64::consts::PI;
            if k >= 3 && (lo < -pi - 1e-9 || hi > pi + 1e-9) {
                return Err(self.invalid(
                    at,
                    format!("angles must be within [-pi, pi], got [{lo}, {hi}]"),
                ));
            }
            bounds[k] = (lo, hi);
        }
        Ok(Grasp(Wgr {
            x_0w: isometry_from_xyz_rpy(g.frame.xyz, g.frame.rpy),
            x_se: isometry_from_xyz_rpy(g.end_effector.xyz, g.end_effector.rpy),
            bounds,
        }))
    }

    fn robot(
        &self,
        spec: &RobotSpec,
        table: &Table,
        planner: &PlannerSpec,
        settings: &ProjectionSettings,
    ) -> Result<(Robot, DVector<f64>)> {
        match spec {
            RobotSpec::Arm {
                urdf,
                base_pose,
                start_joints,
                end_effector,
                srdf,
                group,
                tool,
                pushing_plane,
            } => {
                for (f, v) in [
                    ("robot.base_pose.xyz", base_pose.xyz),
                    ("robot.base_pose.rpy", base_pose.rpy),
                    ("robot.tool.xyz", tool.xyz),
                    ("robot.tool.rpy", tool.rpy),
                    (
                        "robot.pushing_plane.orientation_rpy",
                        pushing_plane.orientation_rpy,
                    ),
                ] {
                    self.finite(f, &v)?;
                }
                self.finite("robot.pushing_plane.height", &[pushing_plane.height])?;
                self.finite("robot.start_joints", start_joints)?;
                let urdf_path = self.relative(urdf);
                if let Some(why) = crate::input::not_a_regular_file(&urdf_path) {
                    return Err(
                        self.invalid("robot.urdf", format!("file {}: {why}", urdf_path.display()))
                    );
                }
                let base = isometry_from_xyz_rpy(base_pose.xyz, base_pose.rpy);
                let srdf = self.srdf(srdf.as_deref(), &urdf_path)?;
                // The SRDF's chain group names the arm when it is asked for, or when the
                // scene names no end effector.
                let chain_group = match (&srdf, group, end_effector) {
                    (None, Some(_), _) => {
                        return Err(self.invalid(
                            "robot.group",
                            "names an SRDF group, but there is no SRDF (robot.srdf, or a .srdf file beside the URDF)",
                        ))
                    }
                    (None, None, None) => {
                        return Err(self.invalid(
                            "robot.end_effector",
                            "missing (the end-effector link; or an SRDF whose chain group ends in it)",
                        ))
                    }
                    (Some((srdf, srdf_path)), group, None) | (Some((srdf, srdf_path)), group @ Some(_), _) => {
                        Some(srdf.chain(group.as_deref()).map_err(|message| {
                            self.invalid("robot.group", format!("{}: {message}", srdf_path.display()))
                        })?)
                    }
                    _ => None,
                };
                let end_effector: &str = match (end_effector, &chain_group) {
                    (Some(link), _) => link,
                    (None, Some((_, tip))) => tip,
                    (None, None) => unreachable!("refused above"),
                };
                let chain_base = chain_group.as_ref().map(|(base, _)| base.as_str());
                // A link the URDF lacks is the scene's fault: its field is named.
                let chain = load_urdf_chain(&urdf_path, chain_base, end_effector, base).map_err(
                    |e| match e {
                        Error::NoEndEffector { file, message } => self.invalid(
                            match chain_group {
                                Some(_) => "robot.group",
                                None => "robot.end_effector",
                            },
                            format!("{}: {message}", file.display()),
                        ),
                        e => e,
                    },
                )?;
                let ee_link = chain
                    .link_index(end_effector)
                    .expect("checked by load_urdf");
                if chain.dof() == 0 {
                    return Err(self.invalid(
                        "robot.end_effector",
                        format!("no movable joint between the root link and '{end_effector}'"),
                    ));
                }
                if start_joints.len() != chain.dof() {
                    return Err(self.invalid(
                        "robot.start_joints",
                        format!(
                            "{} values given, the chain to '{end_effector}' has {} joints",
                            start_joints.len(),
                            chain.dof()
                        ),
                    ));
                }
                let [r, p, y] = pushing_plane.orientation_rpy;
                let plane = PushingPlane::new(
                    table.top + pushing_plane.height,
                    UnitQuaternion::from_euler_angles(r, p, y),
                );
                let mut robot = Robot::new(
                    RobotKind::Arm,
                    chain,
                    ee_link,
                    isometry_from_xyz_rpy(tool.xyz, tool.rpy),
                    plane,
                    settings.clone(),
                );
                if let Some((srdf, srdf_path)) = &srdf {
                    disable_collisions(&mut robot, srdf, srdf_path)?;
                }
                let mut q = DVector::from_column_slice(start_joints);
                let written = q.clone();
                if let Err(failure) = robot.start_on_plane(&mut q) {
                    self.start_problem(self.invalid("robot.start_joints", format!("the tool cannot be brought onto its pushing plane from here ({failure}); `pushplan robot SCENE --reach X,Y` prints starts on it")))?;
                    q = written.clone();
                }
                if let Err(problem) =
                    self.within_joint_limits("robot.start_joints", " (on the plane)", &robot, &q)
                {
                    self.start_problem(problem)?;
                    q = written;
                }
                Ok((robot, q))
            }
            RobotSpec::PlanarHand {
                shape,
                start,
                height,
            } => {
                self.finite("robot.start", start)?;
                self.length("robot.height", *height)?;
                let (primitive, _) = self.shape("robot.shape", shape, true)?;
                let geometry = self.geometry("robot.shape", &primitive, Isometry3::identity())?;
                let chain = planar_hand_chain(
                    table.top + height,
                    table.x,
                    table.y,
                    vec![geometry],
                    planner.max_ee_speed,
                    planner.max_ee_turn_rate,
                );
                let plane = PushingPlane::new(table.top + height, UnitQuaternion::identity());
                let ee_link = chain.links.len() - 1;
                let robot = Robot::new(
                    RobotKind::PlanarHand,
                    chain,
                    ee_link,
                    Isometry3::identity(),
                    plane,
                    settings.clone(),
                );
                let q = DVector::from_column_slice(&[
                    start[0],
                    start[1],
                    crate::math::wrap_angle(start[2]),
                ]);
                if robot.chain.within_limits(&q).is_err() {
                    return Err(self.invalid("robot.start", "the hand starts off the table"));
                }
                Ok((robot, q))
            }
        }
    }

    fn goal(
        &self,
        g: &GoalSpec,
        objects: &[MovableObject],
        table: &Table,
        dof: usize,
    ) -> Result<Goal> {
        if g.object_may_move.is_some() {
            return Err(self.invalid("goal.object_may_move", "applies to grasp goals only"));
        }
        match (&g.object, &g.configuration) {
            (Some(name), None) => {
                if g.tolerance.is_some() {
                    return Err(
                        self.invalid("goal.tolerance", "applies to configuration goals only")
                    );
                }
                let object = objects
                    .iter()
                    .position(|o| &o.name == name)
                    .ok_or_else(|| {
                        self.invalid(
                            "goal.object",
                            format!(
                                "no movable object named '{name}'; the objects are {}",
                                name_list(objects.iter().map(|o| o.name.as_str()))
                            ),
                        )
                    })?;
                let center = g.center.ok_or_else(|| {
                    self.invalid("goal.center", "missing (the goal disc's centre [x, y])")
                })?;
                self.finite("goal.center", &center)?;
                let radius = g.radius.ok_or_else(|| {
                    self.invalid("goal.radius", "missing (the goal disc's radius)")
                })?;
                self.length("goal.radius", radius)?;
                let margin = g.margin.unwrap_or_else(|| default_goal_margin(radius));
                if !(margin.is_finite() && (0.0..radius).contains(&margin)) {
                    return Err(self.invalid(
                        "goal.margin",
                        format!("must be zero or positive and less than goal.radius ({radius}), got {margin}"),
                    ));
                }
                let center = Vector2::new(center[0], center[1]);
                if !table.contains(center) {
                    return Err(self.invalid(
                        "goal.center",
                        format!("({}, {}) is off the table", center.x, center.y),
                    ));
                }
                Ok(Goal::ObjectInDisc {
                    object,
                    center,
                    radius,
                    margin,
                })
            }
            (None, Some(q)) => {
                if g.center.is_some() || g.radius.is_some() || g.margin.is_some() {
                    return Err(self.invalid(
                        "goal",
                        "give either object/center/radius/margin or configuration, not both",
                    ));
                }
                self.finite("goal.configuration", q)?;
                if q.len() != dof {
                    return Err(self.invalid(
                        "goal.configuration",
                        format!("{} values given, the robot has {dof} joints", q.len()),
                    ));
                }
                let tolerance = g.tolerance.unwrap_or(0.05);
                self.positive("goal.tolerance", tolerance)?;
                Ok(Goal::Configuration {
                    q: DVector::from_column_slice(q),
                    tolerance,
                })
            }
            (Some(_), Some(_)) => {
                Err(self.invalid("goal", "give either object or configuration, not both"))
            }
            (None, None) => Err(self.invalid(
                "goal",
                "needs object (with center and radius) or configuration",
            )),
        }
    }

    /// `goal: {grasp: OBJECT, object_may_move: false}`: reach one of the object's grasps.
    fn grasp_goal(
        &self,
        g: &GoalSpec,
        name: &str,
        objects: &[MovableObject],
        table: &Table,
        robot: &Robot,
    ) -> Result<Goal> {
        if g.object.is_some()
            || g.center.is_some()
            || g.radius.is_some()
            || g.margin.is_some()
            || g.configuration.is_some()
            || g.tolerance.is_some()
        {
            return Err(self.invalid(
                "goal",
                "a grasp goal has grasp and object_may_move only (no object, center, radius, margin, configuration or tolerance)",
            ));
        }
        let graspable = || {
            name_list(
                objects
                    .iter()
                    .filter(|o| !o.grasps.is_empty())
                    .map(|o| o.name.as_str()),
            )
        };
        let object = objects
            .iter()
            .position(|o| o.name == name && !o.grasps.is_empty())
            .ok_or_else(|| {
                self.invalid(
                    "goal.grasp",
                    format!(
                        "no movable object '{name}' with grasps; objects with grasps: {}",
                        graspable()
                    ),
                )
            })?;
        Ok(Goal::Grasp {
            object,
            grasps: objects[object].grasps.clone(),
            object_may_move: g.object_may_move.unwrap_or(false),
            table_top: table.top,
            robot: crate::scene::SharedRobot(std::sync::Arc::new(robot.clone())),
        })
    }

    fn planner(&self, p: &PlannerSpec) -> Result<PlannerSpec> {
        for (field, value) in [
            ("planner.time_limit", p.time_limit),
            ("planner.step", p.step),
            ("planner.min_duration", p.min_duration),
            ("planner.max_duration", p.max_duration),
            ("planner.max_ee_speed", p.max_ee_speed),
            ("planner.max_ee_turn_rate", p.max_ee_turn_rate),
            ("planner.robot_weight", p.robot_weight),
            ("planner.object_weight", p.object_weight),
            ("planner.goal_object_weight", p.goal_object_weight),
            ("planner.rotation_length", p.rotation_length),
        ] {
            self.positive(field, value)?;
        }
        if !(p.max_nullspace_speed.is_finite() && p.max_nullspace_speed >= 0.0) {
            return Err(self.invalid(
                "planner.max_nullspace_speed",
                format!("must be zero or positive, got {}", p.max_nullspace_speed),
            ));
        }
        if !(0.0..=1.0).contains(&p.goal_bias) {
            return Err(self.invalid(
                "planner.goal_bias",
                format!("must be in [0, 1], got {}", p.goal_bias),
            ));
        }
        if p.k == 0 || p.k > MAX_K {
            return Err(self.invalid("planner.k", format!("must be in [1, {MAX_K}], got {}", p.k)));
        }
        self.within(
            "planner.step",
            p.step,
            MIN_STEP,
            MAX_STEP,
            "s per propagation step",
        )?;
        // The tool's travel in one step bounds how far a link can jump past an object
        // between two collision checks: at most what the longest step allows at the
        // default speed (0.1 s x 0.5 m/s).
        for (field, speed, most, unit) in [
            ("planner.max_ee_speed", p.max_ee_speed, MAX_STEP_TRAVEL, "m"),
            (
                "planner.max_ee_turn_rate",
                p.max_ee_turn_rate,
                MAX_STEP_TURN,
                "rad",
            ),
            (
                "planner.max_nullspace_speed",
                p.max_nullspace_speed,
                MAX_STEP_TURN,
                "rad",
            ),
        ] {
            if speed * p.step > most {
                return Err(self.invalid(
                    field,
                    format!(
                        "{speed} x planner.step {} s moves {} {unit} in one step; at most {most} {unit}, \
                         or a link passes through an object between two checks",
                        p.step,
                        speed * p.step
                    ),
                ));
            }
        }
        if p.max_duration / p.step > MAX_CONTROL_STEPS as f64 {
            return Err(self.invalid(
                "planner.max_duration",
                format!(
                    "{} s is {:.0} steps of planner.step; a control has at most {MAX_CONTROL_STEPS}",
                    p.max_duration,
                    p.max_duration / p.step
                ),
            ));
        }
        if p.min_duration > p.max_duration {
            return Err(self.invalid(
                "planner.min_duration",
                "must not exceed planner.max_duration",
            ));
        }
        if p.min_duration < p.step {
            return Err(self.invalid(
                "planner.min_duration",
                "must be at least one propagation step (planner.step)",
            ));
        }
        Ok(*p)
    }

    fn physics(&self, p: &PhysicsSpec) -> Result<PhysicsSpec> {
        for (field, value) in [
            ("physics.contact_margin", p.contact_margin),
            ("physics.penetration_tolerance", p.penetration_tolerance),
            ("physics.overlap_tolerance", p.overlap_tolerance),
            ("physics.vertical_normal_angle", p.vertical_normal_angle),
            ("physics.max_joint_speed", p.max_joint_speed),
            ("physics.plane_tolerance", p.plane_tolerance),
            ("physics.tilt_tolerance", p.tilt_tolerance),
        ] {
            self.positive(field, value)?;
        }
        if !(p.tipping_margin.is_finite() && (0.0..1.0).contains(&p.tipping_margin)) {
            return Err(self.invalid(
                "physics.tipping_margin",
                format!("must be in [0, 1), got {}", p.tipping_margin),
            ));
        }
        for (field, value) in [
            ("physics.object_clearance", p.object_clearance),
            ("physics.edge_clearance", p.edge_clearance),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(self.invalid(field, format!("must be zero or positive, got {value}")));
            }
        }
        if !(p.arm_clearance.is_finite() && (0.0..=p.contact_margin).contains(&p.arm_clearance)) {
            return Err(self.invalid(
                "physics.arm_clearance",
                format!(
                    "must be in [0, physics.contact_margin = {}], got {}",
                    p.contact_margin, p.arm_clearance
                ),
            ));
        }
        self.positive("physics.t_max", p.t_max)?;
        if p.model == PhysicsModel::SemiDynamic && p.object_clearance > 0.0 {
            return Err(self.invalid(
                "physics.object_clearance",
                format!(
                    "must be 0 with physics.model: semi_dynamic (objects push one another), got {}",
                    p.object_clearance
                ),
            ));
        }
        if p.penetration_tolerance >= p.contact_margin {
            return Err(self.invalid(
                "physics.penetration_tolerance",
                "must be smaller than physics.contact_margin",
            ));
        }
        Ok(p.clone())
    }
}

/// Leaves the SRDF's `disable_collisions` pairs out of `robot`'s self-collision checks; a
/// link the URDF lacks is an error naming the SRDF's element (the two files do not
/// belong together).
fn disable_collisions(robot: &mut Robot, srdf: &Srdf, path: &Path) -> Result<()> {
    let links = &robot.chain.links;
    let mut pairs = Vec::with_capacity(srdf.disabled.len());
    for (i, pair) in srdf.disabled.iter().enumerate() {
        let index = |name: &str, attribute: &str| {
            links.iter().position(|l| l.name == name).ok_or_else(|| {
                Error::invalid(
                    path,
                    format!("disable_collisions[{i}].{attribute}"),
                    format!(
                        "no link named '{name}' in the URDF (is this the SRDF of another robot?); the links are {}",
                        name_list(links.iter().map(|l| l.name.as_str()))
                    ),
                )
            })
        };
        let (a, b) = (index(&pair.link1, "link1")?, index(&pair.link2, "link2")?);
        pairs.push((a, b));
    }
    robot.skip_self_collisions(&pairs);
    Ok(())
}
