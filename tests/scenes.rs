use pushplan::Scene;
#[test]
fn shipped_scenes_load() {
    for f in [
        "herb_fig1_clutter",
        "herb_fig6_low_clutter",
        "herb_single_object",
        "planar_hand_single_object",
    ] {
        let s = Scene::load(format!("scenes/{f}.yaml"));
        match s {
            Ok(s) => println!("{f}: ok, q = {:?}", s.start.q.as_slice()),
            Err(e) => panic!("{e}"),
        }
    }
}
