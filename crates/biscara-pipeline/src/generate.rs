//! `biscara gen`: pick-and-place points → CL → G-code in one streaming pass.

use std::io::{BufRead, Write};

use biscara_cl::write_statement;
use biscara_kinematics::Kinematics;
use biscara_pnp::{ClProgram, PointsError};
use biscara_post::{PostError, PostOptions, Postprocessor};

/// A failure of [`generate`]: in the points file, in the postprocessor (at a line of the CL
/// stream), or writing the CL copy.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GenerateError {
    /// Occurs when the points file is wrong (its `Display` starts with the line).
    #[error(transparent)]
    Points(#[from] PointsError),
    /// Occurs when the postprocessor refuses a statement.
    #[error(transparent)]
    Post(#[from] PostError),
    /// Occurs when the CL copy cannot be written.
    #[error("cannot write the CL file: {0}")]
    ClOutput(std::io::Error),
}

/// Points file → G-code in one streaming pass (`biscara gen`): the CL statements of
/// [`ClProgram`] go straight to the [`Postprocessor`], and to `cl_out` as CL text
/// when given.
pub fn generate(
    input: impl BufRead,
    model: &Kinematics,
    out: &mut dyn Write,
    mut cl_out: Option<&mut dyn Write>,
    options: PostOptions,
) -> Result<(), GenerateError> {
    let mut post = Postprocessor::new(out, options);
    let mut cl_line = 0;
    for statement in ClProgram::new(input, model) {
        let statement = statement?;
        cl_line += 1;
        if let Some(cl_out) = cl_out.as_mut() {
            write_statement(cl_out, &statement).map_err(GenerateError::ClOutput)?;
        }
        post.apply(cl_line, &statement)?;
    }
    post.finish(cl_line)?;
    if let Some(cl_out) = cl_out {
        cl_out.flush().map_err(GenerateError::ClOutput)?;
    }
    Ok(())
}
