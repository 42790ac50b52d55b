use std::io::Read;
use std::sync::Arc;

use super::*;
use crate::verify::plan_from_zip;
use platener_fixtures::samples;

#[test]
fn the_box_becomes_a_zip_with_six_parts_on_sheets() {
    let source = Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    let c = convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts");
    let bundle = c.export.as_ref().expect("exported");
    assert_eq!(bundle.plan.parts.len(), 6);
    let names: Vec<&str> = c.records.iter().map(|s| s.name).collect();
    assert_eq!(
        names,
        [
            "read", "cleanup", "weld", "mesh", "coplanar", "shapes", "plates", "bends", "joints", "parts", "kerf",
            "labels", "sheets", "export"
        ]
    );
    // The ZIP holds plan.json, which lists the same six parts.
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bundle.zip.clone())).expect("a ZIP");
    let mut plan = String::new();
    zip.by_name("plan.json")
        .expect("plan.json")
        .read_to_string(&mut plan)
        .expect("utf-8");
    let plan: serde_json::Value = serde_json::from_str(&plan).expect("JSON");
    assert_eq!(plan["parts"].as_array().expect("parts").len(), 6);
    assert_eq!(plan["method"], "plate");
    // Twelve finger-jointed edges, each naming its two parts and the 90° they enclose.
    let joints = plan["joints"].as_array().expect("joints");
    assert_eq!(joints.len(), 12);
    for j in joints {
        assert_eq!(j["kind"], "finger");
        assert!((j["angle"].as_f64().expect("angle") - 90.0).abs() < 1e-6);
    }
}

#[test]
fn plan_json_reads_back_as_a_plan() {
    let source = Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    let c = convert(MethodKind::Plate, source, Settings::default(), &Cancel::default()).expect("converts");
    let bundle = c.export.as_ref().expect("exported");
    // No key twice (a flattened settings object could repeat one), and every field parses back.
    let plan = plan_from_zip(&bundle.zip).expect("plan.json parses");
    assert_eq!(plan.parts.len(), bundle.plan.parts.len());
    assert_eq!(plan.joints, bundle.plan.joints);
    assert_eq!(plan.settings.method, bundle.plan.settings.method);
    assert!(plan.settings.method.contains_key("offered_thicknesses"));
    // report.json carries the coverage report: every one of the box's 12 faces used by a plate.
    let report: serde_json::Value = serde_json::from_slice(&bundle.files["report.json"]).expect("JSON");
    let shapes = report["method_report"]["coverage"]["shapes"]
        .as_array()
        .expect("coverage");
    assert_eq!(shapes.len(), 12);
    assert!(
        shapes
            .iter()
            .all(|s| !s["plates"].as_array().expect("plates").is_empty())
    );
    assert_eq!(
        report["method_report"]["connections"]
            .as_array()
            .expect("connections")
            .len(),
        12
    );
}

fn box_request(methods: Vec<MethodKind>) -> Request {
    let source = Source::triangles("box", samples::closed_box(100.0, 80.0, 60.0, 3.0));
    Request {
        methods,
        ..Request::new(source, Settings::default())
    }
}

#[test]
fn the_shared_steps_run_once_and_every_method_starts_from_them() {
    // A textured box, so the classifier runs (it skips exact faces).
    let source = Source::triangles(
        "textured",
        samples::textured_box(glam::DVec3::new(120.0, 90.0, 70.0), 3.0, 0.5, 10.0),
    );
    let all = convert_all(
        Request::new(source, Settings::default()),
        &Cancel::default(),
        no_progress(),
    );
    assert_eq!(all.methods.len(), MethodKind::ALL.len());
    let shared = all.shared.as_ref().expect("shared steps ran");
    let read = shared.read.as_ref().expect("read");
    for m in &all.methods {
        assert_eq!(m.status, Status::Converted, "{:?}", m.error);
        let state = m.state.as_ref().expect("state");
        // The very same snapshot, not a second reading.
        assert!(Arc::ptr_eq(read, state.read.as_ref().expect("read")));
        assert!(Arc::ptr_eq(
            shared.cleanup.as_ref().expect("cleanup"),
            state.cleanup.as_ref().expect("cleanup")
        ));
        assert!(m.score.is_some());
    }
    // The stacked method welds exact duplicates only: its own weld snapshot.
    let weld = |k: usize| {
        all.methods[k]
            .state
            .as_ref()
            .and_then(|s| s.weld.clone())
            .expect("weld")
    };
    assert!(!Arc::ptr_eq(&weld(0), &weld(1)));
    // The classifier welds as the stacked method does: their weld and mesh were made once.
    assert!(Arc::ptr_eq(&weld(1), &weld(2)));
    let mesh = |k: usize| {
        all.methods[k]
            .state
            .as_ref()
            .and_then(|s| s.mesh.clone())
            .expect("mesh")
    };
    assert!(Arc::ptr_eq(&mesh(1), &mesh(2)));
}

#[test]
fn convert_all_gives_the_same_zip_as_one_method_alone() {
    let all = convert_all(box_request(MethodKind::ALL.to_vec()), &Cancel::default(), no_progress());
    for m in all.methods.iter().filter(|m| m.status != Status::Skipped) {
        let alone = convert_all(box_request(vec![m.method]), &Cancel::default(), no_progress());
        let (a, b) = (m.bundle().expect("zip"), alone.methods[0].bundle().expect("zip"));
        assert_eq!(a.zip, b.zip, "{}", m.method.name());
    }
}

#[test]
fn events_name_every_step_and_method_in_order() {
    let seen = Arc::new(std::sync::Mutex::new(Vec::new()));
    let sink = {
        let seen = seen.clone();
        move |e: Event<'_>| {
            let line = match e {
                Event::Step {
                    method,
                    event: StepEvent::Finished(r),
                } => format!("{}:{}", method.map_or("shared", MethodKind::name), r.name),
                Event::Step { .. } => return,
                Event::Shared(state) => format!("shared ended, read: {}", state.read.is_some()),
                Event::Method(m) => format!("{} {:?}", m.method.name(), m.status),
            };
            seen.lock().expect("not poisoned").push(line);
        }
    };
    convert_all(box_request(vec![MethodKind::Plate]), &Cancel::default(), Arc::new(sink));
    let seen = seen.lock().expect("not poisoned").clone();
    assert_eq!(
        seen,
        [
            "shared:read",
            "shared:cleanup",
            "shared ended, read: true",
            "plate:weld",
            "plate:mesh",
            "plate:coplanar",
            "plate:shapes",
            "plate:plates",
            "plate:bends",
            "plate:joints",
            "plate:parts",
            "plate:kerf",
            "plate:labels",
            "plate:sheets",
            "plate:export",
            "plate Converted"
        ]
    );
}

#[test]
fn a_failing_panicking_or_hanging_method_leaves_the_others_converted() {
    for (kind, status) in [
        (FaultKind::Error, Status::Failed),
        (FaultKind::Panic, Status::Panicked),
        (FaultKind::Hang, Status::TimedOut),
    ] {
        let request = Request {
            faults: vec![Fault {
                method: MethodKind::Plate,
                kind,
            }],
            timeout: (kind == FaultKind::Hang).then(|| std::time::Duration::from_millis(300)),
            methods: vec![MethodKind::Plate],
            ..box_request(Vec::new())
        };
        let all = convert_all(request.clone(), &Cancel::default(), no_progress());
        assert_eq!(all.methods[0].status, status, "{kind:?}: {:?}", all.methods[0].error);
        assert!(all.best.is_none());
        // The other method still runs and converts, a hanging one's time limit its own.
        let two = Request {
            methods: vec![MethodKind::Plate, MethodKind::Stacked],
            timeout: (kind == FaultKind::Hang).then(|| std::time::Duration::from_secs(15)),
            ..request
        };
        let all = convert_all(two, &Cancel::default(), no_progress());
        assert_eq!(all.methods[0].status, status, "{kind:?}");
        assert_eq!(
            all.methods[1].status,
            Status::Converted,
            "{kind:?}: {:?}",
            all.methods[1].error
        );
        assert_eq!(all.best, Some(MethodKind::Stacked));
    }
}

/// A method past its time limit no longer starves the others (issue 29): the stacked plan's
/// event comes while the hanging plate method still runs, and only the plate method is
/// reported timed out, after it.
#[test]
fn a_method_past_its_limit_times_out_alone_and_the_others_report_first() {
    let seen = Arc::new(std::sync::Mutex::new(Vec::new()));
    let sink = {
        let seen = seen.clone();
        move |e: Event<'_>| {
            if let Event::Method(m) = e {
                seen.lock().expect("not poisoned").push((m.method, m.status));
            }
        }
    };
    let request = Request {
        faults: vec![Fault {
            method: MethodKind::Plate,
            kind: FaultKind::Hang,
        }],
        timeout: Some(std::time::Duration::from_secs(15)),
        ..box_request(vec![MethodKind::Plate, MethodKind::Stacked])
    };
    let all = convert_all(request, &Cancel::default(), Arc::new(sink));
    let seen = seen.lock().expect("not poisoned").clone();
    assert_eq!(
        seen,
        [
            (MethodKind::Stacked, Status::Converted),
            (MethodKind::Plate, Status::TimedOut)
        ]
    );
    assert_eq!(
        all.method(MethodKind::Stacked).map(|m| m.status),
        Some(Status::Converted)
    );
}

/// With one method at a time, each still gets its whole limit from its own start.
#[test]
fn methods_run_one_at_a_time_when_asked_each_with_its_own_limit() {
    let request = Request {
        faults: vec![Fault {
            method: MethodKind::Plate,
            kind: FaultKind::Hang,
        }],
        timeout: Some(std::time::Duration::from_secs(15)),
        parallel: 1,
        ..box_request(vec![MethodKind::Plate, MethodKind::Stacked])
    };
    let all = convert_all(request, &Cancel::default(), no_progress());
    assert_eq!(all.methods[0].status, Status::TimedOut);
    // The stacked method started when the plate method's time was up, with 15 s of its own.
    assert_eq!(all.methods[1].status, Status::Converted, "{:?}", all.methods[1].error);
    // One after the other: the call lasted both.
    assert!(all.seconds >= all.methods[0].seconds + all.methods[1].seconds);
}

/// A model no sheet holds is refused by every method right after its outlines are known,
/// before joints, shafts and nesting (issue 29: a workbench frame took minutes to say so).
#[test]
fn a_workbench_no_sheet_holds_is_refused_by_every_method_before_the_costly_steps() {
    let source = Source::triangles("workbench", samples::workbench());
    let all = convert_all(
        Request::new(source, Settings::default()),
        &Cancel::default(),
        no_progress(),
    );
    for m in &all.methods {
        let error = m.error.as_ref().map(ToString::to_string).unwrap_or_default();
        match m.method {
            // Nothing in a workbench for the classifier to replace.
            MethodKind::Classifier => assert_eq!(m.status, Status::Skipped, "{error}"),
            _ => {
                assert_eq!(m.status, Status::Failed, "{}", m.method.name());
                assert!(error.contains("does not fit a 600 × 400 mm sheet"), "{error}");
                let steps: Vec<&str> = m.steps().iter().map(|r| r.name).collect();
                assert!(!steps.contains(&"joints") && !steps.contains(&"sheets"), "{steps:?}");
            }
        }
    }
    // The plate method names a plate of the frame's long side: 1526 − 6 mm long at least.
    let plate = all
        .method(MethodKind::Plate)
        .and_then(|m| m.error.as_ref())
        .expect("refused");
    let long: f64 = plate
        .to_string()
        .split(" is ")
        .nth(1)
        .and_then(|s| s.split(" × ").next())
        .and_then(|s| s.parse().ok())
        .expect("a size in the message");
    assert!((1500.0..=1526.0).contains(&long), "{plate}");
}

/// The classifier skips a model whose faces are exact, with the reason, and no method counts
/// that as a failure.
#[test]
fn the_classifier_skips_exact_faces_and_says_why() {
    let all = convert_all(
        box_request(vec![MethodKind::Plate, MethodKind::Classifier]),
        &Cancel::default(),
        no_progress(),
    );
    let m = &all.methods[1];
    assert_eq!(m.status, Status::Skipped);
    let reason = m.error.as_ref().map(ToString::to_string).unwrap_or_default();
    assert!(reason.contains("faces are exact"), "{reason}");
    // It stopped before sampling: no classify snapshot.
    assert!(m.state.as_ref().is_none_or(|s| s.classify.is_none()));
    // Asked for alone, it runs: nothing else would make the plan.
    let alone = convert_all(
        box_request(vec![MethodKind::Classifier]),
        &Cancel::default(),
        no_progress(),
    );
    assert_eq!(
        alone.methods[0].status,
        Status::Converted,
        "{:?}",
        alone.methods[0].error
    );
}

#[test]
fn a_cancelled_conversion_says_so() {
    let cancel = Cancel::default();
    cancel.cancel();
    let all = convert_all(box_request(vec![MethodKind::Plate]), &cancel, no_progress());
    assert_eq!(all.methods[0].status, Status::Cancelled);
}

#[test]
fn an_unreadable_upload_fails_every_method_naming_the_file() {
    let request = Request::new(
        Source::Bytes {
            name: "broken.stl".into(),
            bytes: Arc::from(&b"solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 nope\n"[..]),
        },
        Settings::default(),
    );
    let all = convert_all(request, &Cancel::default(), no_progress());
    for m in &all.methods {
        assert_eq!(m.status, Status::Failed);
        let error = m.error.as_ref().expect("an error");
        assert_eq!(error.culprit(), crate::error::Culprit::Model);
        let text = error.to_string();
        assert!(text.contains("broken.stl") && text.contains("line"), "{text}");
    }
}

/// The order the sheets are offered in never changes a plan: a solid block (all extruded
/// plates, whose thickness used to be the first offered) and the stacked method's layers.
#[test]
fn the_order_of_the_offered_sheets_changes_nothing() {
    let block = samples::cuboid(glam::DVec3::ZERO, glam::DVec3::new(80.0, 60.0, 40.0));
    let zips = |thicknesses: Vec<f64>| {
        let source = Source::triangles("block", block.clone());
        let settings = Settings {
            thicknesses,
            ..Settings::default()
        };
        let all = convert_all(Request::new(source, settings), &Cancel::default(), no_progress());
        all.methods
            .iter()
            .filter(|m| m.status != Status::Skipped)
            .map(|m| m.bundle().expect("converted").zip.clone())
            .collect::<Vec<_>>()
    };
    let (a, b) = (zips(vec![3.0, 6.0]), zips(vec![6.0, 3.0, 6.0]));
    // The classifier skips a block's exact faces: plate, stacked and interlocked.
    assert_eq!(a.len(), 3);
    assert_eq!(a, b);
    // The thinnest sheet is the one used.
    let source = Source::triangles("block", block.clone());
    let settings = Settings {
        thicknesses: vec![6.0, 3.0],
        ..Settings::default()
    };
    let state = convert(MethodKind::Plate, source, settings, &Cancel::default()).expect("converts");
    assert!(
        state
            .bundle()
            .expect("plan")
            .plan
            .parts
            .iter()
            .all(|p| p.thickness == 3.0)
    );
}

/// A plan `verify` fails is never named best over one it passes, whatever their scores.
#[test]
fn a_plan_verify_fails_is_not_named_best_over_one_it_passes() {
    let request = box_request(vec![MethodKind::Plate, MethodKind::Stacked]);
    let all = convert_all(request, &Cancel::default(), no_progress());
    let mut methods = all.methods.clone();
    let verdict = |m: &MethodResult| m.verification.as_ref().expect("verified").clone();
    let (plate, stacked) = (&methods[0], &methods[1]);
    assert_eq!((plate.method, stacked.method), (MethodKind::Plate, MethodKind::Stacked));
    // The jointed plates pass, and so do the box's stacked rings (pegs in bosses hold them).
    assert!(verdict(plate).passed(), "{:?}", verdict(plate).problems);
    assert!(verdict(stacked).passed(), "{:?}", verdict(stacked).problems);
    assert_eq!(all.best, Some(MethodKind::Plate));
    // A plan without its joints falls apart and fails verify.
    let without_joints = |m: &mut MethodResult| {
        let mut plan = m.bundle().expect("plan").plan.clone();
        plan.joints.clear();
        let analysis = crate::assembly::analyse(&plan, m.state.as_ref().and_then(|s| s.mesh.as_deref()));
        m.verification = Some(crate::verify::check(&plan, &analysis, crate::verify::MIN_COVERAGE));
    };
    without_joints(&mut methods[1]);
    assert!(!verdict(&methods[1]).passed());
    // Even with a perfect score the failing stacked plan is not named best over the plates.
    methods[1].score.as_mut().expect("score").total = 1.0;
    assert_eq!(best_of(&methods), Some(MethodKind::Plate));
    // When neither passes (the plates without their joints too), the score decides again.
    without_joints(&mut methods[0]);
    assert!(!verdict(&methods[0]).passed());
    assert_eq!(best_of(&methods), Some(MethodKind::Stacked));
}
