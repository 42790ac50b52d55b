//! The settings described for front ends: JSON for `GET /api/settings` (the page's form is
//! built from it) and the Markdown table of docs/settings.md.

use std::fmt::Write as _;

use serde_json::{Value, json};

use super::{DEFS, Def, Group, Kind};

/// Every group and setting, as `GET /api/settings` answers: `groups` in form order (`id`,
/// `label`, `folded`) and `settings` in [`DEFS`]' order (`name`, `key`, `label`, `group`,
/// `kind` with its values or range, `default`, `help`, `doc`, `repeatable`).
pub fn schema() -> Value {
    let groups: Vec<Value> = Group::ALL
        .iter()
        .map(|g| json!({ "id": g, "label": g.label(), "folded": g.folded() }))
        .collect();
    let settings: Vec<Value> = DEFS.iter().map(describe).collect();
    json!({ "groups": groups, "settings": settings })
}

fn describe(def: &Def) -> Value {
    json!({
        "name": def.name,
        "key": def.key,
        "label": def.label,
        "group": def.group,
        "kind": def.kind,
        "default": def.default_value(),
        "repeatable": def.repeatable(),
        "help": def.help,
        "doc": def.doc,
    })
}

/// The values a setting takes, in words: `wood, acrylic, …`, `0.1–50 mm`.
pub fn values_in_words(def: &Def) -> String {
    match def.kind {
        Kind::Choice { choices } => choices.iter().map(|c| c.value).collect::<Vec<_>>().join(", "),
        Kind::Number { unit, min, max, auto } => {
            let auto = if auto.is_some() { "auto or " } else { "" };
            format!("{auto}{min}–{max} {unit}")
        }
        Kind::Numbers {
            unit,
            min,
            max,
            max_count,
            ..
        } => format!("1–{max_count} values, each {min}–{max} {unit}"),
        Kind::Sheet { max, .. } => format!("WxH in mm (each side ≤ {max}) or fit"),
        Kind::Text { format, .. } => format.to_string(),
    }
}

/// The table of every setting for docs/settings.md (a test keeps the file equal to it).
pub fn markdown() -> String {
    let mut out = String::from(
        "# Settings\n\n\
         Generated from the library's one definition of each setting (`platener::options`); the CLI's \
         flags, the web API's fields and the page's form are made from the same definitions. \
         `cargo test -p platener options` fails when this file is out of date; \
         `PLATENER_BLESS=1` rewrites it.\n",
    );
    for group in Group::ALL {
        let _ = write!(
            out,
            "\n## {}\n\n| setting | CLI | values | default | what it does |\n|---|---|---|---|---|\n",
            group.label()
        );
        for def in DEFS.iter().filter(|d| d.group == group) {
            let flag = match def.short {
                Some(c) => format!("`-{c}`, `--{}`", def.name),
                None => format!("`--{}`", def.name),
            };
            let _ = writeln!(
                out,
                "| {} (`{}`) | {flag} | {} | {} | {} {} |",
                def.label,
                def.key,
                values_in_words(def),
                def.default_texts().join(", "),
                def.help,
                def.doc
            );
        }
    }
    out
}
