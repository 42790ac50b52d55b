//! The summary stored with each conversion: one typed contract between the worker, which
//! writes it as the conversion goes (`worker::live`) and when it ends (`results`), and the
//! server, which reads it back for the conversion JSON, the gallery and the best plan's files
//! (issue 33). Before, each side spelt the keys itself (`json!` on one side, `summary["best"]`
//! on the other). The JSON is the API's (docs/api.md: a conversion's `model`, `steps`,
//! `methods`, `best`).

use serde::{Deserialize, Serialize};
use serde_json::Value;

/// What a conversion made so far, or in the end.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// The model as read; `None` before `read` (or when it could not read it).
    #[serde(default)]
    pub model: Option<ModelLine>,
    /// The shared steps that ran.
    #[serde(default)]
    pub steps: Vec<StepLine>,
    /// One line per method ended, in the order asked for.
    #[serde(default)]
    pub methods: Vec<MethodLine>,
    /// The best method's name, once the conversion ended with a plan.
    #[serde(default)]
    pub best: Option<String>,
    /// The conversion's wall time, s, once it ended.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seconds: Option<f64>,
}

/// The model as read.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ModelLine {
    /// Triangles read.
    pub triangles: usize,
    /// Its box's size, mm.
    pub bbox_mm: [f64; 3],
}

/// One shared step that ran.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StepLine {
    /// The step's name (report.json's).
    pub name: String,
    /// Its wall time, ms.
    pub ms: f64,
    /// Its warnings, as report.json has them.
    pub warnings: Vec<Value>,
}

/// One method's result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MethodLine {
    /// The method's name.
    pub method: String,
    /// `done`, `failed`, `panicked`, `timed-out`, `cancelled` or `skipped`
    /// (`results::status_name`).
    pub status: String,
    /// Its plan's score.
    pub score: Option<f64>,
    /// Parts in its plan.
    pub parts: Option<usize>,
    /// Sheets in its plan.
    pub sheets: Option<usize>,
    /// "glue-free" or what glue it needs.
    pub glue: Option<String>,
    /// Whether its plan passed `verify`.
    pub verified: Option<bool>,
    /// Its wall time, s.
    pub seconds: f64,
    /// Its warnings (left out of the `method` event, which the conversion JSON completes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warnings: Option<Vec<Value>>,
    /// Why it made no plan.
    pub error: Option<String>,
}

impl Summary {
    /// The summary stored as `text`; the empty summary when there is none or it does not
    /// parse (a row written before the conversion started).
    pub fn parse(text: Option<&str>) -> Summary {
        text.and_then(|s| serde_json::from_str(s).ok()).unwrap_or_default()
    }

    /// The best method's line.
    pub fn best_line(&self) -> Option<&MethodLine> {
        let best = self.best.as_deref()?;
        self.methods.iter().find(|m| m.method == best)
    }

    /// As stored: JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|_| "{}".to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(method: &str) -> MethodLine {
        MethodLine {
            method: method.into(),
            status: "done".into(),
            score: Some(0.9),
            parts: Some(6),
            sheets: Some(1),
            glue: Some("glue-free".into()),
            verified: Some(true),
            seconds: 0.1,
            warnings: Some(Vec::new()),
            error: None,
        }
    }

    #[test]
    fn a_summary_reads_back_what_was_written_and_finds_its_best() {
        let summary = Summary {
            model: Some(ModelLine {
                triangles: 12,
                bbox_mm: [10.0, 20.0, 30.0],
            }),
            steps: vec![StepLine {
                name: "read".into(),
                ms: 1.5,
                warnings: Vec::new(),
            }],
            methods: vec![line("plate"), line("stacked")],
            best: Some("stacked".into()),
            seconds: Some(0.3),
        };
        let back = Summary::parse(Some(&summary.to_json()));
        assert_eq!(back, summary);
        assert_eq!(back.best_line().map(|m| m.method.as_str()), Some("stacked"));
    }

    #[test]
    fn no_summary_or_a_broken_one_reads_as_empty() {
        assert_eq!(Summary::parse(None), Summary::default());
        assert_eq!(Summary::parse(Some("not json")), Summary::default());
        let running = Summary::parse(Some(r#"{"model": null, "steps": [], "methods": [], "best": null}"#));
        assert!(running.best_line().is_none() && running.model.is_none());
    }
}
