//! `dynamics excite --plot`'s SVG (issue 28): a well-formed document
//! (read back by an independent XML parser) with three panels, one line
//! per joint in each (positions, velocities, efforts) whose points are the
//! design's samples, and one shaded limit band per joint and panel where
//! the limit is finite.

use dynamics_cli::excite::{limits, plot};
use dynamics_runtime::Robot;
use dynamics_sim2real::excite::{design, Options};
use robots::builtin::motion;
use robots::registry::AnyRobot;

fn check<R: Robot<N> + Sync, const N: usize>(robot: &R, name: &str) {
    let lim = limits::<N>(
        AnyRobot::by_name(name).expect("robot").limits().as_ref(),
        &motion(name),
    );
    let mut o = Options::new(5.0);
    o.evaluations = 40;
    let d = design(robot, &lim, &o).unwrap_or_else(|e| panic!("{name}: {e}"));
    let text = plot(robot, &d);
    let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    let panels: Vec<_> = root
        .children()
        .filter(|n| n.tag_name().name() == "svg")
        .collect();
    assert_eq!(panels.len(), 3, "{name}");
    for (p, panel) in panels.iter().enumerate() {
        let lines: Vec<_> = panel
            .descendants()
            .filter(|n| n.tag_name().name() == "polyline")
            .collect();
        assert_eq!(lines.len(), N, "{name}: panel {p}");
        for line in &lines {
            let points = line.attribute("points").expect("points");
            let n = points.split_whitespace().count();
            assert!((1000..=2001).contains(&n), "{name}: panel {p}: {n} points");
            for xy in points.split_whitespace() {
                let (x, y) = xy.split_once(',').expect("x,y");
                assert!(x.parse::<f64>().is_ok_and(f64::is_finite), "{xy}");
                assert!(y.parse::<f64>().is_ok_and(f64::is_finite), "{xy}");
            }
        }
        // The legend names every joint; every joint's band is labelled.
        let texts: Vec<&str> = panel.descendants().filter_map(|n| n.text()).collect();
        for j in R::JOINT_NAMES {
            assert!(texts.contains(&j), "{name}: panel {p}: no legend {j}");
            let finite = match p {
                0 => true,
                1 => d.limits.velocity.iter().all(|v| v.is_finite()),
                _ => d.limits.effort.iter().all(|v| v.is_finite()),
            };
            let label = format!("{j} limits");
            assert_eq!(
                texts.contains(&label.as_str()),
                finite,
                "{name}: panel {p}: {label}"
            );
        }
    }
}

#[test]
fn excite_plot_is_well_formed_with_one_line_per_joint() {
    for name in ["arm3r", "panda"] {
        let robot = AnyRobot::by_name(name).expect("robot");
        robots::each_robot!(&robot, r => check(r, name));
    }
}
