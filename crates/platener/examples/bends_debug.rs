//! Prints what the bends step made of a sample (a debugging aid).
fn main() {
    let which = std::env::args().nth(1).unwrap_or_default();
    let source = if which == "ball" {
        platener::Source::triangles(
            "ball",
            platener::samples::sphere(platener::glam::DVec3::ZERO, 40.0, 12, 8),
        )
    } else if which.ends_with(".stl") {
        platener::Source::File(which.clone().into())
    } else {
        let model = platener::samples::bent_samples()
            .into_iter()
            .find(|(n, _)| n.starts_with(&which))
            .expect("a sample")
            .1;
        platener::Source::triangles("m", model)
    };
    let mut s = platener::Settings::default();
    if let Some(b) = std::env::args().nth(2) {
        s.bending = b.parse().expect("a --bend value");
    }
    if which.starts_with("cone") {
        s.thicknesses = vec![1.5];
        s.cut.material = platener::plan::Material::Cardboard;
    }
    let state = platener::convert::convert(
        platener::method::MethodKind::Plate,
        source,
        s,
        &platener::Cancel::default(),
    )
    .expect("converts");
    let bundle = state.export.as_ref().unwrap();
    let plan = &bundle.plan;
    let score = platener::score::score(state.mesh.as_ref().unwrap(), bundle, state.plates.as_deref());
    println!(
        "cut {:.0} mm engrave {:.0} mm score {:.3}",
        bundle.report.cut_length, bundle.report.engrave_length, score.total
    );
    let v = platener::verify::verify(plan, state.mesh.as_deref());
    println!(
        "parts {} covered {:?} inside {:?} groups {} interference {:.4} problems {:?}",
        plan.parts.len(),
        v.surface_covered,
        v.volume_inside,
        v.groups,
        v.interference_share,
        v.problems
    );
    for p in plan.parts.iter().filter(|p| !p.segments.is_empty()) {
        println!("bent part {} merged {:?}", p.id, p.merged);
    }
    for j in plan.joints.iter().filter(|j| v.joints_not_meeting.contains(&j.label)) {
        println!("unmet joint {:?}", j);
    }
    if std::env::var_os("PIECES").is_some() {
        pieces_report(plan);
    }
    let plates = &state.plates.as_ref().unwrap().plates;
    println!("plates {}", plates.len());
    let b = state.bends.as_ref().unwrap();
    println!("candidates {} parts {}", b.candidates, b.parts.len());
    for p in &b.parts {
        let m: Vec<u32> = p.members.iter().map(|m| m.plate + 1).collect();
        println!("part {m:?} bends {} seams {}", p.bends.len(), p.seams.len());
        for bl in &p.bends {
            println!(
                "  bend {:?} enclosed {:.1} width {:.2} r {:.2} gap {:.2}",
                bl.members,
                bl.enclosed_deg,
                bl.zone.width,
                bl.zone.radius,
                bl.zone.corner_gap()
            );
        }
    }
    for r in &b.refused {
        println!("refused {:?}: {}", r.plates.map(|p| p + 1), r.reason);
    }
    for (i, p) in plates.iter().enumerate() {
        println!("plate {} area {:.0} n {:.2?}", i + 1, p.area, p.frame.n);
    }
    for w in state.records.iter().flat_map(|r| r.warnings.iter()) {
        println!("warning: {}", w.message);
    }
}

#[allow(dead_code)]
fn pieces_report(plan: &platener::plan::Plan) {
    for p in &plan.parts {
        let Ok(pieces) = p.pieces() else {
            println!("part {} pieces fail", p.id);
            continue;
        };
        for (k, s) in pieces.iter().enumerate() {
            let (lo, hi) = s.polygon.bounds();
            let c = (lo + hi) / 2.0;
            let m = s
                .frame
                .to_model(platener::glam::DVec3::new(c.x, c.y, s.thickness / 2.0));
            let r = (m.x * m.x + m.y * m.y).sqrt();
            println!(
                "part {} piece {k}: r {:.2} z {:.1} area {:.0}",
                p.id,
                r,
                m.z,
                s.polygon.area()
            );
        }
    }
}
