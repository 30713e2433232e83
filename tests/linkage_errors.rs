//! Bad linkage scenes: each gives a clear error naming the file and the field (or the
//! constraint), exit code 2, and writes nothing.

mod common;

use std::path::Path;

fn shaper_text() -> String {
    std::fs::read_to_string(common::root().join("templates/shaper.toml")).unwrap()
}

/// Runs `mechdraw run` on `text`; returns stderr after checking exit code 2 and that the
/// output directory was not created.
fn run_bad(text: &str) -> String {
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("bad.toml");
    std::fs::write(&scene, text).unwrap();
    let out_dir = tmp.path().join("out");
    let out = common::mechdraw().arg("run").arg(&scene).arg("--out").arg(&out_dir).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(stderr.contains("bad.toml"), "the file is not named: {stderr}");
    assert!(
        !Path::new(&out_dir).exists() || std::fs::read_dir(&out_dir).unwrap().next().is_none(),
        "something was written"
    );
    stderr
}

#[test]
fn unknown_body_in_a_joint() {
    let e = run_bad(
        &shaper_text().replace("revolute = [\"crank.A\", \"block.A\"]", "revolute = [\"crank.A\", \"blok.A\"]"),
    );
    assert!(e.contains("joint[1].revolute[1]"), "{e}");
    assert!(e.contains("unknown body `blok`") && e.contains("block"), "{e}");
}

#[test]
fn point_that_does_not_exist() {
    let e = run_bad(
        &shaper_text().replace("revolute = [\"rocker.B\", \"link.B\"]", "revolute = [\"rocker.C\", \"link.B\"]"),
    );
    assert!(e.contains("joint[4].revolute[0]"), "{e}");
    assert!(e.contains("body `rocker` has no point `C`; its points are: O3, B"), "{e}");
}

#[test]
fn expression_that_does_not_parse_shows_where() {
    let e = run_bad(&shaper_text().replace("law = \"2*pi*t\"", "law = \"2*pi*t +\""));
    assert!(e.contains("driver[0].law"), "{e}");
    assert!(e.contains("column 9") && e.contains("  2*pi*t +\n          ^"), "{e}");
    let e = run_bad(&shaper_text().replace("law = \"2*pi*t\"", "law = \"2*pi*tt\""));
    assert!(e.contains("unknown name `tt`") && e.contains("column 6"), "{e}");
}

#[test]
fn degrees_of_freedom_that_do_not_match_the_drivers() {
    let text = shaper_text();
    let i = text.find("[[driver]]").unwrap();
    let j = text.find("[[measure]]").unwrap();
    let no_driver = format!("{}{}", &text[..i], &text[j..]);
    let e = run_bad(&no_driver);
    assert!(e.contains("field `driver`") && e.contains("1 degree of freedom") && e.contains("0 drivers"), "{e}");
    assert!(e.contains("add 1 driver"), "{e}");
    let two = text.replace("[[measure]]\npoint", "[[driver]]\nbody = \"rocker\"\nlaw = \"t\"\n\n[[measure]]\npoint");
    let e = run_bad(&two);
    assert!(e.contains("remove 1 driver"), "{e}");
}

#[test]
fn start_that_cannot_be_assembled() {
    // The link BE cannot reach the ram's line when it is 20 mm long.
    // The run names the Assur group that cannot close, its joint and the time.
    let e = run_bad(&shaper_text().replace("E = [150.0, 0.0]", "E = [20.0, 0.0]"));
    assert!(e.contains("the dyad RRP (link, ram) cannot be assembled at t = 0 s"), "{e}");
    assert!(e.contains("joint `E` cannot close") && e.contains("does not reach the line of `ram-guide`"), "{e}");
}

#[test]
fn a_joint_with_both_kinds_or_none() {
    let e = run_bad(&shaper_text().replace(
        "name = \"A\"\nrevolute",
        "name = \"A\"\nprismatic = { point = \"block.A\", line = [\"rocker.O3\", \"rocker.B\"] }\nrevolute",
    ));
    assert!(e.contains("joint[1]") && e.contains("exactly one of"), "{e}");
}

#[test]
fn bad_drag_option() {
    let tmp = tempfile::tempdir().unwrap();
    let out = common::mechdraw()
        .args(["run", "templates/shaper.toml", "--drag", "crank.Z=1,2", "--out"])
        .arg(tmp.path().join("o"))
        .current_dir(common::root())
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{e}");
    assert!(e.contains("--drag crank.Z=1,2") && e.contains("no point `Z`"), "{e}");
}

#[test]
fn more_steps_than_a_run_draws() {
    // 4000 steps would be 4001 frames, each carrying the whole paths: refused before
    // anything is written, naming the field and the limit.
    let e = run_bad(&shaper_text().replace("steps = 360", "steps = 4000"));
    assert!(e.contains("field `time.steps`") && e.contains("4001 positions") && e.contains("at most 3600"), "{e}");
    // The limit itself is drawn.
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("ok.toml");
    std::fs::write(&scene, shaper_text().replace("steps = 360", "steps = 3599")).unwrap();
    let mut cmd = common::mechdraw();
    cmd.args(["run", "-q", "--no-frames", "--out"]).arg(tmp.path().join("o")).arg(&scene);
    assert!(cmd.status().unwrap().success());
}

#[test]
fn a_time_step_too_coarse_for_newton_suggests_more_steps() {
    // 360 steps over 1000 s: the crank turns 2.8 times between samples, so the general
    // solver's Newton from the previous position cannot follow; the error says where and
    // what to change. The run's Assur groups solve every sample in closed form, each dyad
    // on its branch (tests/linkage_assur.rs checks the positions), so the run succeeds.
    let text = shaper_text().replace("to = 1.0, steps = 360", "to = 1000.0, steps = 360");
    let mechdraw::scene::Scene::Linkage(s) = mechdraw::scene::parse(&text, "coarse.toml", &[]).unwrap() else {
        panic!("not a linkage scene")
    };
    let e = mechdraw::solve::linkage::Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap_err();
    let e = e.to_string();
    assert!(e.contains("did not converge at t = 2.77") && e.contains("try more time steps"), "{e}");
    let tmp = tempfile::tempdir().unwrap();
    let scene = tmp.path().join("coarse.toml");
    std::fs::write(&scene, text).unwrap();
    let mut cmd = common::mechdraw();
    cmd.args(["run", "-q", "--no-frames", "--out"]).arg(tmp.path().join("o")).arg(&scene);
    assert!(cmd.status().unwrap().success());
}

fn forces_text() -> String {
    std::fs::read_to_string(common::root().join("templates/shaper-forces.toml")).unwrap()
}

/// Replaces `from` (which must occur) in the shaper-forces template and runs it as a bad scene.
fn run_bad_forces(from: &str, to: &str) -> String {
    let text = forces_text();
    assert!(text.contains(from), "`{from}` is not in the template");
    run_bad(&text.replacen(from, to, 1))
}

#[test]
fn negative_mass_or_inertia() {
    let e = run_bad_forces("mass = 20.0", "mass = -20.0");
    assert!(e.contains("field `body[2].mass`") && e.contains("≥ 0") && e.contains("-20"), "{e}");
    let e = run_bad_forces("inertia = 0.35", "inertia = -0.35");
    assert!(e.contains("field `body[0].inertia`") && e.contains("≥ 0"), "{e}");
}

#[test]
fn inertia_missing_where_it_has_no_default() {
    // A three-point body with a mass: the bar's m·l²/12 does not apply.
    let e = run_bad_forces(
        "points = { B = [0.0, 0.0], E = [150.0, 0.0] }",
        "points = { B = [0.0, 0.0], E = [150.0, 0.0], K = [75.0, 20.0] }",
    );
    assert!(e.contains("field `body[3].inertia`") && e.contains("moment of inertia"), "{e}");
}

#[test]
fn load_at_an_unknown_point_or_on_the_ground() {
    let e = run_bad_forces("at = \"ram.T\"", "at = \"ram.X\"");
    assert!(e.contains("field `load[0].at`") && e.contains("body `ram` has no point `X`; its points are: E, T"), "{e}");
    let e = run_bad_forces("at = \"ram.T\"", "at = \"ground.O1\"");
    assert!(e.contains("field `load[0].at`") && e.contains("on the ground does nothing"), "{e}");
    let e = run_bad_forces("at = \"ram.T\"", "at = \"rame.T\"");
    assert!(e.contains("unknown body `rame`"), "{e}");
}

#[test]
fn load_expression_that_does_not_parse_shows_where() {
    let e = run_bad_forces("force = [3000.0, 0.0]      # N", "force = [\"3000*(1 - t\", 0.0]");
    assert!(e.contains("field `load[0].force[0]`") && e.contains("cannot parse the expression"), "{e}");
    assert!(e.contains("  3000*(1 - t\n"), "{e}");
}

#[test]
fn load_window_from_after_to() {
    let e = run_bad_forces("t = [0.0, 0.568]", "t = [0.568, 0.0]");
    assert!(e.contains("field `load[0].t`") && e.contains("from > to"), "{e}");
}

#[test]
fn load_with_both_or_neither_of_force_and_torque() {
    let e = run_bad_forces("force = [3000.0, 0.0]      # N", "force = [3000.0, 0.0]\nbody = \"ram\"\ntorque = 5.0");
    assert!(e.contains("field `load[0]`") && e.contains("give either a force"), "{e}");
    let e = run_bad_forces("force = [3000.0, 0.0]      # N", "");
    assert!(e.contains("field `load[0]`") && e.contains("give either a force"), "{e}");
}

#[test]
fn load_not_finite_while_solving() {
    // Finite at parse time, infinite at the sample t = 0.5 s.
    let e = run_bad_forces("force = [3000.0, 0.0]      # N", "force = [\"3000/(t - 0.5)\", 0.0]");
    assert!(e.contains("load `cut`") && e.contains("not finite at t = 0.5 s"), "{e}");
}
