//! Every shipped scene loads, with a valid start state that does not already satisfy its
//! goal (each is a planning problem).

use pushplan_model::Scene;

#[test]
fn shipped_scenes_are_planning_problems() {
    let mut files: Vec<std::path::PathBuf> = ["scenes", "scenes/benchmark"]
        .iter()
        .flat_map(|dir| std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()))
        .filter(|p| p.extension().is_some_and(|x| x == "yaml"))
        .collect();
    files.sort();
    assert!(files.len() >= 4 + 35, "{} scenes", files.len());
    for file in files {
        // Loading checks every field and the start state's validity.
        let scene = Scene::load(&file).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            !scene.goal.is_satisfied(&scene.start),
            "{}: the goal holds at the start",
            file.display()
        );
    }
}
