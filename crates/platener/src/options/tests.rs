use proptest::prelude::*;
use serde_json::json;

use super::*;

/// The setting's name in a refusal (`set` or `validate`), or `None` when accepted.
fn refused(key: &str, value: serde_json::Value) -> Option<&'static str> {
    let mut chosen = Chosen::default();
    match chosen.set_json(key, &value).and_then(|()| chosen.validate()) {
        Ok(()) => None,
        Err(Error::Setting { name, .. }) => Some(name),
        Err(e) => panic!("not a setting error: {e}"),
    }
}

#[test]
fn every_default_is_the_librarys() {
    let mut chosen = Chosen::default();
    for def in DEFS {
        let texts = def.default_texts();
        let refs: Vec<&str> = texts.iter().map(String::as_str).collect();
        chosen.set(def.name, &refs).expect("a default is valid");
    }
    assert_eq!(chosen, Chosen::default());
    assert!(Chosen::default().validate().is_ok());
}

#[test]
fn every_choice_reads_back_as_written() {
    for def in DEFS {
        for choice in def.choices() {
            let mut chosen = Chosen::default();
            chosen.set(def.name, &[choice.value]).expect("a listed choice");
            assert_eq!(def.value(&chosen), json!(choice.value), "{}", def.name);
            assert!(chosen.validate().is_ok(), "{} {}", def.name, choice.value);
        }
        if !def.choices().is_empty() {
            assert_eq!(refused(def.key, json!("<none>")), Some(def.name), "{}", def.name);
        }
    }
}

#[test]
fn number_ranges_are_the_ones_validate_checks() {
    for def in DEFS {
        let (min, max) = match def.kind {
            Kind::Number { min, max, .. } | Kind::Numbers { min, max, .. } => (min, max),
            _ => continue,
        };
        assert_eq!(refused(def.key, json!(min)), None, "{} at its minimum", def.name);
        assert_eq!(refused(def.key, json!(max)), None, "{} at its maximum", def.name);
        assert_eq!(
            refused(def.key, json!(max * 1.01 + 0.01)),
            Some(def.name),
            "{} above",
            def.name
        );
        let below = if min > 0.0 { min * 0.99 } else { -0.01 };
        assert_eq!(refused(def.key, json!(below)), Some(def.name), "{} below", def.name);
        assert_eq!(refused(def.key, json!("ten")), Some(def.name), "{} text", def.name);
    }
    let Kind::Sheet { max, .. } = find("sheet").expect("sheet").kind else {
        panic!("sheet is a sheet")
    };
    assert_eq!(refused("sheet", json!(format!("{max}x{max}"))), None);
    assert_eq!(refused("sheet", json!(format!("{}x400", max + 1.0))), Some("sheet"));
    for preset in match find("sheet").expect("sheet").kind {
        Kind::Sheet { presets, .. } => presets,
        _ => &[],
    } {
        assert_eq!(refused("sheet", json!(preset.value)), None, "{}", preset.value);
    }
}

#[test]
fn thicknesses_take_several_values_and_other_settings_one() {
    let mut chosen = Chosen::default();
    chosen.set_json("thicknesses", &json!([3, 6])).expect("two thicknesses");
    assert_eq!(chosen.settings.thicknesses, vec![3.0, 6.0]);
    chosen.set_json("thickness", &json!(4)).expect("one thickness");
    assert_eq!(chosen.settings.thicknesses, vec![4.0]);
    assert_eq!(refused("thicknesses", json!(vec![3; 11])), Some("thickness"));
    assert_eq!(refused("kerf", json!([0.1, 0.2])), Some("kerf"));
    assert_eq!(refused("material", json!({"x": 1})), Some("material"));
    chosen.set_json("kerf", &json!(null)).expect("auto");
    assert_eq!(chosen.settings.cut.kerf, None);
    chosen.set_json("weld", &json!(0)).expect("off");
    assert_eq!(chosen.settings.weld, crate::Weld::Off);
    chosen.set_json("method", &json!("stacked")).expect("one method");
    assert_eq!(chosen.methods, vec![MethodKind::Stacked]);
}

#[test]
fn unknown_settings_are_refused_with_the_list_and_without_echo() {
    let mut chosen = Chosen::default();
    let e = chosen.set("colour", &["red"]).expect_err("no such setting").to_string();
    assert!(e.contains("colour is no setting") && e.contains("material"), "{e}");
    let e = chosen.set("<b>", &["red"]).expect_err("no such setting").to_string();
    assert!(!e.contains('<'), "{e}");
    let e = chosen
        .set("material", &["<b>gold</b>"])
        .expect_err("no such material")
        .to_string();
    assert!(!e.contains('<') && e.contains("wood, acrylic"), "{e}");
}

#[test]
fn messages_name_settings_as_each_front_end_does() {
    let message = "scale the model up (`scale`) or set `weld` to 0; see `platener help`";
    assert_eq!(
        render(message, |d| format!("--{}", d.name)),
        "scale the model up (--scale) or set --weld to 0; see `platener help`"
    );
    assert_eq!(
        render(message, |d| format!("“{}”", d.label)),
        "scale the model up (“Scale”) or set “Weld distance” to 0; see `platener help`"
    );
    assert_eq!(render("an odd ` backtick", |_| String::new()), "an odd ` backtick");
    let mut chosen = Chosen::default();
    chosen.settings.thicknesses = vec![0.05];
    let e = chosen.validate().expect_err("too thin").to_string();
    assert!(
        render(&e, |d| d.label.to_string()).starts_with("Sheet thickness: "),
        "{e}"
    );
}

/// Messages a person reads name settings, never a CLI flag: the page has no flags.
#[test]
fn library_messages_name_no_command_line_flag() {
    let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut offenders = Vec::new();
    let mut stack = vec![src];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("source dir").flatten() {
            let path = entry.path();
            let name = path
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or_default()
                .to_string();
            if path.is_dir() {
                stack.push(path);
            } else if name.ends_with(".rs") && !name.contains("test") {
                let text = std::fs::read_to_string(&path).expect("source");
                for (i, line) in text.lines().enumerate() {
                    let code = line.trim_start();
                    let flag = code
                        .find("--")
                        .is_some_and(|at| code[at + 2..].starts_with(|c: char| c.is_ascii_lowercase()));
                    if flag && !code.starts_with("//") {
                        offenders.push(format!("{}:{}: {code}", path.display(), i + 1));
                    }
                }
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "library messages naming CLI flags:\n{}",
        offenders.join("\n")
    );
}

#[test]
fn docs_settings_table_is_current() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/settings.md");
    let table = markdown();
    if std::env::var_os("PLATENER_BLESS").is_some() {
        std::fs::write(&path, &table).expect("write docs/settings.md");
    }
    let written = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        written == table,
        "docs/settings.md is out of date: run with PLATENER_BLESS=1"
    );
}

#[test]
fn the_schema_lists_every_setting_in_its_group() {
    let schema = schema();
    let settings = schema["settings"].as_array().expect("settings");
    assert_eq!(settings.len(), DEFS.len());
    let groups: Vec<&str> = schema["groups"]
        .as_array()
        .expect("groups")
        .iter()
        .filter_map(|g| g["id"].as_str())
        .collect();
    for s in settings {
        assert!(groups.contains(&s["group"].as_str().expect("group")), "{s}");
        assert_eq!(
            s["default"],
            find(s["name"].as_str().expect("name")).expect("def").default_value()
        );
    }
    assert_eq!(settings[0]["kind"]["type"], "choice");
}

proptest! {
    /// Whatever number a field gets, it is read back as given (or refused by name).
    #[test]
    fn numbers_read_back_as_set(value in -10.0f64..2000.0) {
        for key in ["scale", "kerf", "weld", "thicknesses"] {
            let mut chosen = Chosen::default();
            chosen.set_json(key, &json!(value)).expect("a number");
            let back = find(key).expect("def").value(&chosen);
            let expected = if key == "thicknesses" { json!([value]) } else { json!(value) };
            prop_assert!(back == expected || (key == "weld" && value == 0.0), "{key}: {back}");
        }
    }
}
