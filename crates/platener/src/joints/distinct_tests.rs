//! Key fingers and the choice of which look-alike joint gets one.

use super::distinct::*;
use crate::verify::Acceptance;

/// A 60 mm joint of 7 segments in 3 mm sheets (finger width 9 mm, narrowest 1.5 mm).
fn look(len: f64) -> Look {
    Look {
        len,
        segments: 7,
        key: None,
        narrowest: 1.5,
        target: 9.0,
        free: true,
        from_high: false,
    }
}

fn fit(joints: [usize; 2], interchangeable: bool) -> Acceptance {
    Acceptance {
        joints,
        sides: [0, 0],
        reversed: false,
        twins: interchangeable.then_some([0, 1]),
    }
}

#[test]
fn a_key_finger_is_wider_and_the_others_share_the_rest() {
    let even = boundaries((10.0, 70.0), 7, None);
    assert_eq!(even.len(), 8);
    assert!(even.windows(2).all(|w| (w[1] - w[0] - 60.0 / 7.0).abs() < 1e-9));
    let keyed = boundaries((10.0, 70.0), 7, Some(KeyFinger { at: 2, wide: 1.5 }));
    let widths: Vec<f64> = keyed.windows(2).map(|w| w[1] - w[0]).collect();
    assert_eq!(keyed[0], 10.0);
    assert_eq!(keyed[7], 70.0);
    assert!((widths[2] - 1.5 * 60.0 / 7.0).abs() < 1e-9, "{widths:?}");
    let other = (60.0 - 1.5 * 60.0 / 7.0) / 6.0;
    for (s, w) in widths.iter().enumerate().filter(|(s, _)| *s != 2) {
        assert!((w - other).abs() < 1e-9, "segment {s}: {widths:?}");
    }
}

#[test]
fn only_joints_that_fit_wrongly_change_and_to_cuts_no_joint_alike_has() {
    let looks = vec![look(60.0); 4];
    // 0 and 1 are twins' joints (harmless); 2 fits 0 and 3 wrongly.
    let found = [fit([0, 1], true), fit([0, 2], false), fit([2, 3], false)];
    let chosen = choose(&looks, &found);
    assert_eq!(chosen[0], None, "a twin stays as it is");
    assert_eq!(chosen[1], None);
    assert_eq!(chosen[3], None, "one of each wrong pair changes");
    let new = chosen[2].expect("the joint that fits two others changes");
    assert_eq!(new.segments, 7);
    let key = new.key.expect("a key finger");
    assert_eq!((key.at, key.wide), (0, 1.5), "the first place, from the lower end");
    // Counted from the joint's other end when its axis runs down.
    let down = vec![
        Look {
            from_high: true,
            ..look(60.0)
        };
        2
    ];
    let key = choose(&down, &[fit([0, 1], false)])[1]
        .and_then(|v| v.key)
        .expect("keyed");
    assert_eq!(key.at, 6);
}

#[test]
fn a_joint_that_may_not_change_leaves_it_to_the_other() {
    let looks = vec![
        look(60.0),
        Look {
            free: false,
            ..look(60.0)
        },
    ];
    let chosen = choose(&looks, &[fit([0, 1], false)]);
    assert!(chosen[0].is_some() && chosen[1].is_none(), "{chosen:?}");
    let fixed = vec![
        Look {
            free: false,
            ..look(60.0)
        };
        2
    ];
    assert_eq!(choose(&fixed, &[fit([0, 1], false)]), vec![None, None]);
}

/// Many joints alike, each fitting the next wrongly: each changed one takes a cut of its
/// own, within the limits (every segment at least half the finger width, no key wider than
/// two), so no two changed joints are alike.
#[test]
fn many_look_alikes_get_cuts_of_their_own_within_the_limits() {
    let looks = vec![look(60.0); 12];
    let found: Vec<Acceptance> = (0..12)
        .flat_map(|i| (i + 1..12).map(move |j| fit([i, j], false)))
        .collect();
    let chosen = choose(&looks, &found);
    let mut seen = Vec::new();
    for v in chosen.iter().flatten() {
        let bounds = boundaries((0.0, 60.0), v.segments, v.key);
        for w in bounds.windows(2).map(|w| w[1] - w[0]) {
            assert!((4.5 - 1e-9..=18.0 + 1e-9).contains(&w), "{v:?}: {w}");
        }
        // Up to turning end for end.
        let id = (
            v.segments,
            v.key.map(|k| (k.at.min(v.segments - 1 - k.at), (k.wide * 10.0) as u32)),
        );
        assert!(!seen.contains(&id), "{v:?} twice");
        seen.push(id);
    }
    assert_eq!(chosen.iter().filter(|c| c.is_some()).count(), 11, "{chosen:?}");
}

/// Twelve joints alike on a 10 mm edge of 1.5 mm sheet have three ways of being cut: they
/// cannot all differ, so none changes (new fingers would not make the plan foolproof).
#[test]
fn look_alikes_that_cannot_all_differ_stay_as_they_are() {
    let short = Look {
        len: 10.4,
        segments: 3,
        narrowest: 1.0,
        target: 4.5,
        ..look(10.4)
    };
    let looks = vec![short; 12];
    let found: Vec<Acceptance> = (0..11).map(|i| fit([i, i + 1], false)).collect();
    assert_eq!(choose(&looks, &found), vec![None; 12]);
    // Two of them can.
    let chosen = choose(&looks[..2], &found[..1]);
    assert!(chosen[1].is_some(), "{chosen:?}");
}
