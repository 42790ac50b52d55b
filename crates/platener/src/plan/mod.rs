//! The plan: parts with their outlines and transforms, joints and sheets, as in plan.json.
