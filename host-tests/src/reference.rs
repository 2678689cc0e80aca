//! First-principles reference solver (f64). Work in progress: the API below is fixed.

/// Solve one collision with the reference solver and report it in the core's
/// `Outcome` type (f32), for display next to the closed-form models.
pub fn collide(params: &cuesight::Params, impact: &cuesight::Impact) -> cuesight::Outcome {
    let _ = (params, impact);
    todo!("reference solver lands shortly")
}
