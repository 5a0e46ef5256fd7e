use pushplan::contact::{
    find_arm_contacts, object_bounds, planar_contacts, ArmBounds, ObjectContacts,
};
use pushplan::physics::object_motion;
use pushplan::physics::tipping::{pusher_forces, support_balance};
use pushplan::plan::PlanFile;
use pushplan::{Propagator, Scene};
use std::path::Path;
fn main() {
    let plan = PlanFile::read(Path::new("/tmp/d.json")).unwrap();
    let scene = Scene::load(plan.scene_path(Path::new("/tmp/d.json"))).unwrap();
    let mut prop = Propagator::new(scene.clone());
    let path = pushplan::path::simulate(&mut prop, &scene.start, &plan.path_controls(), true);
    let st = &path.step_states;
    let target = scene
        .objects
        .iter()
        .position(|o| o.name == std::env::args().nth(1).unwrap())
        .unwrap();
    let body = &scene.objects[target];
    for k in 0..st.len() - 1 {
        let poses = scene.robot.link_poses(&st[k].q);
        let poses_new = scene.robot.link_poses(&st[k + 1].q);
        let mut bounds = ArmBounds::default();
        ArmBounds::compute(&scene, &poses, &mut bounds);
        let mut boxes = Vec::new();
        object_bounds(&scene, &st[k].objects, &mut boxes);
        let mut contacts = Vec::new();
        find_arm_contacts(
            &scene,
            &poses,
            &bounds,
            &st[k].objects,
            &boxes,
            0.02,
            &mut contacts,
        );
        let mine: Vec<_> = contacts
            .iter()
            .copied()
            .filter(|c| c.object == target)
            .collect();
        if mine.is_empty() {
            continue;
        }
        let mut oc = ObjectContacts::default();
        planar_contacts(
            &mine,
            &st[k].objects[target],
            scene.table.top,
            &poses,
            &poses_new,
            0.01,
            &mut oc,
        );
        let m = object_motion(&oc.planar, &body.limit_surface, body.mu_c, 0.01).unwrap();
        if m.twist.is_zero() {
            continue;
        }
        let mut f = Vec::new();
        pusher_forces(&oc.planar, &oc.elevations, &m, &mut f);
        let b = support_balance(body.mass, body.footprint.centroid(), &f);
        let links: Vec<String> = oc
            .links
            .iter()
            .map(|l| scene.robot.chain.links[*l].name.clone())
            .collect();
        println!(
            "step {k}: cop {:.4} (r {:?}) links {:?} heights {:?} lifts {:?} fn {:?}",
            b.p_OP.norm(),
            body.footprint,
            links,
            oc.elevations
                .iter()
                .map(|e| (e.height * 1000.0).round() / 1000.0)
                .collect::<Vec<_>>(),
            oc.elevations
                .iter()
                .map(|e| (e.lift * 100.0).round() / 100.0)
                .collect::<Vec<_>>(),
            m.normal_forces
        );
    }
}
