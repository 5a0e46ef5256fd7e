//! Robots from URDF: joint kinds, limits, meshes (STL, convex hull) and path resolution.

use crate::common;

use nalgebra::{Isometry3, Vector3};
use pushplan_model::robot::urdf::load_urdf;
use pushplan_model::robot::JointKind;
use pushplan_model::Error;
use std::path::Path;

/// Writes a binary STL of an axis-aligned box with the given half extents.
fn write_box_stl(path: &Path, h: [f32; 3]) {
    use stl_io::{Normal, Triangle, Vertex};
    let v = |x: f32, y: f32, z: f32| Vertex::new([x * h[0], y * h[1], z * h[2]]);
    let corners = [
        v(-1., -1., -1.),
        v(1., -1., -1.),
        v(1., 1., -1.),
        v(-1., 1., -1.),
        v(-1., -1., 1.),
        v(1., -1., 1.),
        v(1., 1., 1.),
        v(-1., 1., 1.),
    ];
    let faces = [
        [0, 2, 1],
        [0, 3, 2],
        [4, 5, 6],
        [4, 6, 7],
        [0, 1, 5],
        [0, 5, 4],
        [2, 3, 7],
        [2, 7, 6],
        [1, 2, 6],
        [1, 6, 5],
        [0, 4, 7],
        [0, 7, 3],
    ];
    let triangles: Vec<Triangle> = faces
        .iter()
        .map(|f| Triangle {
            normal: Normal::new([0.0, 0.0, 0.0]),
            vertices: [corners[f[0]], corners[f[1]], corners[f[2]]],
        })
        .collect();
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let mut file = std::fs::File::create(path).unwrap();
    stl_io::write_stl(&mut file, triangles.iter()).unwrap();
}

fn urdf_with_mesh(filename: &str, scale: &str) -> String {
    format!(
        r#"<robot name="r">
  <link name="base"/>
  <link name="arm"><collision><origin xyz="0 0 0.5"/><geometry><mesh filename="{filename}" {scale}/></geometry></collision></link>
  <link name="finger"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="2"/></joint>
  <joint name="wrist" type="prismatic"><parent link="arm"/><child link="finger"/><origin xyz="0 0 1"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.2" effort="1" velocity="0.5"/></joint>
</robot>"#
    )
}

#[test]
fn package_paths_resolve_without_ros_and_meshes_become_convex_hulls() {
    let scratch = common::Scratch::new("test-package");
    let root = scratch.path().to_path_buf();
    write_box_stl(
        &root.join("my_robot_description/meshes/arm.stl"),
        [0.05, 0.1, 0.2],
    );
    let urdf = root.join("my_robot_description/urdf/r.urdf");
    std::fs::create_dir_all(urdf.parent().unwrap()).unwrap();
    std::fs::write(
        &urdf,
        urdf_with_mesh(
            "package://my_robot_description/meshes/arm.stl",
            r#"scale="2 1 1""#,
        ),
    )
    .unwrap();
    let chain = load_urdf(&urdf, "finger", Isometry3::identity()).unwrap();
    assert_eq!(chain.dof(), 2);
    assert_eq!(chain.dof_joint(0).kind, JointKind::Revolute);
    assert_eq!(chain.dof_joint(1).kind, JointKind::Prismatic);
    assert_eq!(
        (
            chain.dof_joint(1).lower,
            chain.dof_joint(1).upper,
            chain.dof_joint(1).max_velocity
        ),
        (0.0, 0.2, 0.5)
    );
    let arm = &chain.links[chain.link_index("arm").unwrap()];
    let aabb = arm.geometry[0].aabb(&Isometry3::identity());
    // Scaled by 2 along x; placed 0.5 up.
    assert!(
        (aabb.maxs.coords - Vector3::new(0.1, 0.1, 0.7)).norm() < 1e-6,
        "{aabb:?}"
    );
    assert!(
        (aabb.mins.coords - Vector3::new(-0.1, -0.1, 0.3)).norm() < 1e-6,
        "{aabb:?}"
    );
    assert_eq!(
        arm.geometry[0].shape.shape_type(),
        parry3d_f64::shape::ShapeType::ConvexPolyhedron
    );
}

#[test]
fn relative_mesh_paths_resolve_against_the_urdf() {
    let scratch = common::Scratch::new("test-relative");
    let root = scratch.path().to_path_buf();
    write_box_stl(&root.join("meshes/arm.stl"), [0.05, 0.05, 0.05]);
    let urdf = root.join("r.urdf");
    std::fs::write(&urdf, urdf_with_mesh("meshes/arm.stl", "")).unwrap();
    assert!(load_urdf(&urdf, "finger", Isometry3::identity()).is_ok());
}

#[test]
fn a_missing_mesh_names_the_urdf_and_the_mesh() {
    let scratch = common::Scratch::new("test-missing-mesh");
    let root = scratch.path().to_path_buf();
    let urdf = root.join("r.urdf");
    std::fs::write(&urdf, urdf_with_mesh("package://nowhere/arm.stl", "")).unwrap();
    let err = load_urdf(&urdf, "finger", Isometry3::identity()).unwrap_err();
    assert!(matches!(err, Error::Mesh { .. }));
    let message = err.to_string();
    assert!(
        message.contains("r.urdf")
            && message.contains("package://nowhere/arm.stl")
            && message.contains("'arm'"),
        "{message}"
    );
    // Where it looked: beside the URDF, then each folder above it.
    let beside = root.join("nowhere/arm.stl");
    assert!(
        message.contains(&format!("{} (not found)", beside.display())),
        "{message}"
    );
}

#[test]
fn a_binary_stl_whose_count_does_not_match_its_size_is_refused() {
    let scratch = common::Scratch::new("test-stl-count");
    let root = scratch.path().to_path_buf();
    let stl = root.join("arm.stl");
    write_box_stl(&stl, [0.05, 0.05, 0.05]);
    let urdf = root.join("r.urdf");
    std::fs::write(&urdf, urdf_with_mesh("arm.stl", "")).unwrap();
    assert!(load_urdf(&urdf, "finger", Isometry3::identity()).is_ok());
    // The same file with a header that claims 2^31 triangles.
    let mut bytes = std::fs::read(&stl).unwrap();
    let real = u32::from_le_bytes(bytes[80..84].try_into().unwrap());
    assert_eq!(
        bytes.len() as u64,
        84 + 50 * u64::from(real),
        "write_box_stl writes binary STL"
    );
    bytes[80..84].copy_from_slice(&(1u32 << 31).to_le_bytes());
    std::fs::write(&stl, &bytes).unwrap();
    let message = load_urdf(&urdf, "finger", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("arm.stl") && message.contains("says 2147483648 triangles"),
        "{message}"
    );
}

/// A visual mesh of a million triangles took half a minute and 800 MB before planning
/// started; past the limit a binary STL is refused from its header, before it is parsed.
#[test]
fn a_mesh_of_more_triangles_than_the_limit_is_refused_with_the_numbers() {
    use pushplan_model::robot::mesh::MAX_MESH_TRIANGLES;
    let scratch = common::Scratch::new("test-stl-triangles");
    let root = scratch.path().to_path_buf();
    let stl = root.join("arm.stl");
    let urdf = root.join("r.urdf");
    std::fs::write(&urdf, urdf_with_mesh("arm.stl", "")).unwrap();
    for (triangles, refused) in [(MAX_MESH_TRIANGLES, false), (MAX_MESH_TRIANGLES + 1, true)] {
        // Triangles of a box, repeated: the box's hull whatever their number.
        write_box_stl(&stl, [0.05, 0.05, 0.05]);
        let bytes = std::fs::read(&stl).unwrap();
        let mut many = bytes[..80].to_vec();
        many.extend((triangles as u32).to_le_bytes());
        for k in 0..triangles {
            let t = 84 + 50 * (k % 12);
            many.extend(&bytes[t..t + 50]);
        }
        std::fs::write(&stl, &many).unwrap();
        let loaded = load_urdf(&urdf, "finger", Isometry3::identity());
        match refused {
            false => assert!(loaded.is_ok(), "{triangles}: {:?}", loaded.err()),
            true => {
                let message = loaded.unwrap_err().to_string();
                assert!(
                    message.contains("arm.stl")
                        && message.contains(&format!("{triangles} triangles"))
                        && message.contains(&format!("at most {MAX_MESH_TRIANGLES}")),
                    "{message}"
                );
            }
        }
    }
}

#[test]
fn a_mesh_that_is_no_regular_file_says_what_it_is() {
    let scratch = common::Scratch::new("test-special-mesh");
    let root = scratch.path().to_path_buf();
    let urdf = root.join("r.urdf");
    // A symbolic link loop, a pipe (which a plain open would wait on for ever), a device.
    std::os::unix::fs::symlink("loop_b.stl", root.join("loop_a.stl")).unwrap();
    std::os::unix::fs::symlink("loop_a.stl", root.join("loop_b.stl")).unwrap();
    let fifo = std::ffi::CString::new(root.join("pipe.stl").to_str().unwrap()).unwrap();
    // SAFETY: a valid C string and mode.
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0);
    std::os::unix::fs::symlink("/dev/null", root.join("device.stl")).unwrap();
    for (mesh, what) in [
        ("loop_a.stl", "a symbolic link loop"),
        ("pipe.stl", "a pipe (FIFO), not a regular file"),
        ("device.stl", "a device, not a regular file"),
        ("gone.stl", "not found"),
    ] {
        std::fs::write(&urdf, urdf_with_mesh(mesh, "")).unwrap();
        let message = load_urdf(&urdf, "finger", Isometry3::identity())
            .unwrap_err()
            .to_string();
        assert!(
            message.contains(mesh) && message.contains(what),
            "{mesh}: {message}"
        );
    }
}

#[test]
fn a_garbage_mesh_is_an_error_not_a_panic() {
    let scratch = common::Scratch::new("test-garbage-mesh");
    let root = scratch.path().to_path_buf();
    std::fs::write(
        root.join("arm.stl"),
        b"solid nonsense\nthis is not an stl\n",
    )
    .unwrap();
    let urdf = root.join("r.urdf");
    std::fs::write(&urdf, urdf_with_mesh("arm.stl", "")).unwrap();
    let err = load_urdf(&urdf, "finger", Isometry3::identity()).unwrap_err();
    assert!(err.to_string().contains("arm.stl"), "{err}");
}

#[test]
fn broken_urdfs_are_errors() {
    let scratch = common::Scratch::new("test-broken");
    let root = scratch.path().to_path_buf();
    let write = |name: &str, text: &str| {
        let path = root.join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let not_xml = write("a.urdf", "<robot name='r'><link name='a'>");
    assert!(matches!(
        load_urdf(&not_xml, "a", Isometry3::identity()),
        Err(Error::Urdf { .. })
    ));
    let two_roots = write(
        "b.urdf",
        "<robot name='r'><link name='a'/><link name='b'/></robot>",
    );
    let message = load_urdf(&two_roots, "b", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(message.contains("several root links"), "{message}");
    let bad_limits = write(
        "c.urdf",
        "<robot name='r'><link name='a'/><link name='b'/><joint name='j' type='revolute'><parent link='a'/><child link='b'/><axis xyz='0 0 1'/><limit lower='1' upper='-1' effort='1' velocity='1'/></joint></robot>",
    );
    let message = load_urdf(&bad_limits, "b", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("joint 'j'") && message.contains("lower"),
        "{message}"
    );
    let floating = write(
        "d.urdf",
        "<robot name='r'><link name='a'/><link name='b'/><joint name='j' type='floating'><parent link='a'/><child link='b'/></joint></robot>",
    );
    let message = load_urdf(&floating, "b", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(message.contains("not supported"), "{message}");
}

#[test]
fn urdfs_that_ros_loads_load_here() {
    // What ROS's urdfdom accepts: a fixed joint's axis is not read (Franka's public URDF
    // writes `0 0 0` on panda_joint8), a continuous joint needs no <limit>, a joint with
    // no <axis> turns about x, an axis of any length is a direction.
    let scratch = common::Scratch::new("test-urdf-ros");
    let path = scratch.join("r.urdf");
    let joint = |name: &str, kind: &str, parent: &str, child: &str, extra: &str| {
        format!("<joint name='{name}' type='{kind}'><parent link='{parent}'/><child link='{child}'/>{extra}</joint>")
    };
    // A floating joint off the chain (a free part of the model, as simulators' URDFs
    // have) is held where its origin puts it.
    let text = format!(
        "<robot name='r'><link name='a'/><link name='b'/><link name='c'/><link name='d'/><link name='e'/><link name='free'/><link name='finger'/>{}{}{}{}{}{}</robot>",
        joint("loose", "floating", "a", "free", "<origin xyz='1 0 0'/>"),
        joint("grip", "prismatic", "e", "finger", "<axis xyz='0 1 0'/><limit lower='0' upper='0' effort='1' velocity='1'/>"),
        joint("spin", "continuous", "a", "b", "<axis xyz='0 0 1'/>"),
        joint("bend", "revolute", "b", "c", "<limit lower='-1' upper='1' effort='1' velocity='1'/>"),
        joint("long", "revolute", "c", "d", "<axis xyz='0 2 0'/><limit lower='-1' upper='1' effort='1' velocity='1'/>"),
        joint("flange", "fixed", "d", "e", "<origin xyz='0 0 0.1'/><axis xyz='0 0 0'/>"),
    );
    std::fs::write(&path, text).unwrap();
    let chain = load_urdf(&path, "e", Isometry3::identity()).unwrap();
    assert_eq!(chain.dof(), 3);
    let axis = |name: &str| {
        let joint = chain
            .links
            .iter()
            .find_map(|l| l.joint.as_ref().filter(|j| j.name == name))
            .unwrap();
        (
            joint.kind,
            joint.axis.into_inner(),
            joint.lower,
            joint.upper,
        )
    };
    assert_eq!(axis("spin").0, JointKind::Revolute);
    assert_eq!(
        (axis("spin").2, axis("spin").3),
        (-std::f64::consts::PI, std::f64::consts::PI)
    );
    assert_eq!(axis("bend").1, Vector3::x());
    assert_eq!(axis("long").1, Vector3::y());
    assert_eq!(axis("flange").0, JointKind::Fixed);
    assert_eq!(axis("loose").0, JointKind::Fixed);
    let message = load_urdf(&path, "free", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains(
            "floating joints are not supported between the root link and the end effector"
        ),
        "{message}"
    );

    // A joint that moves needs a direction to move about.
    let zero = format!(
        "<robot name='r'><link name='a'/><link name='b'/>{}</robot>",
        joint(
            "j",
            "revolute",
            "a",
            "b",
            "<axis xyz='0 0 0'/><limit lower='-1' upper='1' effort='1' velocity='1'/>"
        )
    );
    std::fs::write(&path, zero).unwrap();
    let message = load_urdf(&path, "b", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("r.urdf")
            && message.contains("joint 'j'")
            && message.contains("axis must not be zero on a revolute joint"),
        "{message}"
    );
}

#[test]
fn urdfs_that_are_not_one_tree_are_errors_naming_the_links() {
    let scratch = common::Scratch::new("test-urdf-tree");
    let write = |name: &str, text: &str| {
        let path = scratch.join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let joint = |name: &str, parent: &str, child: &str| {
        format!("<joint name='{name}' type='fixed'><parent link='{parent}'/><child link='{child}'/></joint>")
    };
    let links = |names: &[&str]| -> String {
        names
            .iter()
            .map(|n| format!("<link name='{n}'/>"))
            .collect()
    };
    // The reproducer: the first joint's parent is the hand, so the arm is a cycle cut off
    // from the base. It panicked while loading the scene.
    let cycle = write(
        "cycle.urdf",
        &format!(
            "<robot name='r'>{}{}{}{}</robot>",
            links(&["base", "l1", "hand"]),
            joint("j1", "hand", "l1"),
            joint("j2", "l1", "hand"),
            ""
        ),
    );
    let message = load_urdf(&cycle, "hand", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("cycle.urdf")
            && message.contains("'l1', 'hand' are not connected to the root link 'base'"),
        "{message}"
    );
    let twice = write(
        "twice.urdf",
        &format!(
            "<robot name='r'>{}{}</robot>",
            links(&["a", "b", "a"]),
            joint("j", "a", "b")
        ),
    );
    let message = load_urdf(&twice, "b", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(message.contains("two links are named 'a'"), "{message}");
    let joints_twice = write(
        "joints_twice.urdf",
        &format!(
            "<robot name='r'>{}{}{}</robot>",
            links(&["a", "b", "c"]),
            joint("j", "a", "b"),
            joint("j", "b", "c")
        ),
    );
    let message = load_urdf(&joints_twice, "c", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(message.contains("two joints are named 'j'"), "{message}");
    let chain = write(
        "chain.urdf",
        &format!(
            "<robot name='r'>{}{}{}</robot>",
            links(&["a", "b", "c"]),
            joint("j1", "a", "b"),
            joint("j2", "b", "c")
        ),
    );
    let message = load_urdf(&chain, "hand", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("no link named 'hand'") && message.contains("'a', 'b', 'c'"),
        "the links there are are listed: {message}"
    );
}

#[test]
fn a_long_chain_of_links_loads_and_too_many_links_are_refused() {
    // 20 000 fixed links took more than 20 s (quadratic); a chain at the limit loads.
    let scratch = common::Scratch::new("test-urdf-chain");
    let chain = |n: usize| {
        let mut text = String::from("<robot name='r'><link name='l0'/>");
        for i in 1..n {
            text += &format!(
                "<link name='l{i}'/><joint name='j{i}' type='fixed'><parent link='l{}'/><child link='l{i}'/></joint>",
                i - 1
            );
        }
        text + "</robot>"
    };
    let limit = pushplan_model::robot::urdf::MAX_LINKS;
    let at_limit = scratch.join("at_limit.urdf");
    std::fs::write(&at_limit, chain(limit)).unwrap();
    let loaded = load_urdf(&at_limit, &format!("l{}", limit - 1), Isometry3::identity()).unwrap();
    assert_eq!(loaded.links.len(), limit);
    let beyond = scratch.join("beyond.urdf");
    std::fs::write(&beyond, chain(20_000)).unwrap();
    let message = load_urdf(&beyond, "l1", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("20000 links; a robot has at most 1000"),
        "{message}"
    );
}

#[test]
fn a_flat_mesh_is_an_error() {
    let scratch = common::Scratch::new("test-flat-mesh");
    // A box squashed to zero height: every vertex on one plane.
    write_box_stl(&scratch.join("flat.stl"), [0.05, 0.05, 0.0]);
    let urdf = scratch.join("r.urdf");
    std::fs::write(&urdf, urdf_with_mesh("flat.stl", "")).unwrap();
    let message = load_urdf(&urdf, "finger", Isometry3::identity())
        .unwrap_err()
        .to_string();
    assert!(message.contains("flat"), "{message}");
}

#[test]
fn scene_obstacles_can_be_stl_meshes() {
    use pushplan_model::{validity::check_state, Invalid, Scene};
    let scratch = common::Scratch::new("test-scene-mesh");
    let root = scratch.path().to_path_buf();
    write_box_stl(&root.join("meshes/crate.stl"), [0.05, 0.05, 0.05]);
    let scene_text = std::fs::read_to_string("scenes/planar_hand_single_object.yaml")
        .unwrap()
        .replace("../robots", "robots")
        + "obstacles:\n  - {name: crate, shape: {type: mesh, file: meshes/crate.stl, scale: [2, 2, 2]}, pose: {xyz: [0.4, 0.4, 0.86]}}\n";
    let path = root.join("scene.yaml");
    std::fs::write(&path, scene_text).unwrap();
    let scene = Scene::load(&path).unwrap();
    // A 0.2 m crate centred at (0.4, 0.4): the hand inside it is invalid, beside it is not.
    let mut state = scene.start.clone();
    state.q[1] = 0.4;
    assert!(
        matches!(check_state(&scene, &state), Err(Invalid::ArmHitsObstacle { obstacle, .. }) if obstacle == "crate")
    );
    state.q[1] = 0.4 - 0.1 - 0.06 - 0.005;
    assert_eq!(check_state(&scene, &state), Ok(()));
}
