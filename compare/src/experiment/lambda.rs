//! lambda of Eq. (76) as a scene gives it ([`LambdaSpec`]) and the project's calibrated
//! table of lambda(H).

use crate::checks::{bad, positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use mrd::roughness::{Lambda, LambdaTable};
use serde::Deserialize;

/// The project's own lambda(H), calibrated by the `fig6-converged` study at bandwidth 128
/// (provenance in the file).
pub const DEFAULT_LAMBDA_CSV: &str = include_str!("../../data/lambda_calibrated.csv");

/// The same study's lambda(H) at each of its bandwidths, 32 to 256 (provenance in the
/// file): what a sweep at one of those bandwidths is held against.
pub const LAMBDA_BY_BANDWIDTH_CSV: &str = include_str!("../../data/lambda_by_bandwidth.csv");

/// lambda of Eq. (76) as written, C1D = lambda q C2D of the same C2D, the line not
/// rescaled ([`super::lambda_meaning`]): a number, "pi" (Eq. 73), "cut" (straight cut),
/// "calibrated" (the embedded table from the `fig6-converged` study), or the path of a
/// CSV table `hurst, lambda` (relative to the scene), e.g. a sweep's
/// `<label>_lambda_table.csv`.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum LambdaSpec {
    Value(f64),
    Named(String),
}

impl Default for LambdaSpec {
    fn default() -> Self {
        LambdaSpec::Named("pi".into())
    }
}

impl LambdaSpec {
    /// Checks every entry of `specs` before a run: at least one, numbers > 0, tables
    /// readable and covering each of `hurst`.
    pub fn check_all(specs: &[LambdaSpec], ctx: &Context, hurst: &[f64]) -> Result<()> {
        if specs.is_empty() {
            return bad("lambda = []: give at least one value (a number, \"pi\", \"cut\", \"calibrated\" or a table's path)".to_string());
        }
        for l in specs {
            if let LambdaSpec::Value(v) = l {
                if !positive(*v) {
                    return bad(format!("lambda = {v} must be > 0"));
                }
            }
            let law = l.build(ctx)?;
            for &h in hurst {
                law.at(h).ctx(format!("lambda {l:?} at H = {h}"))?;
            }
        }
        Ok(())
    }

    /// lambda of each of `specs` at each of `hurst` (`[spec][hurst]`).
    pub fn per_hurst(specs: &[LambdaSpec], ctx: &Context, hurst: &[f64]) -> Result<Vec<Vec<f64>>> {
        specs
            .iter()
            .map(|l| {
                let law = l.build(ctx)?;
                hurst.iter().map(|&h| law.at(h).ctx("lambda")).collect()
            })
            .collect()
    }

    /// lambda of each of `specs` at the one Hurst exponent `hurst`.
    pub fn at_hurst(specs: &[LambdaSpec], ctx: &Context, hurst: f64) -> Result<Vec<f64>> {
        specs
            .iter()
            .map(|l| l.build(ctx)?.at(hurst).ctx("lambda"))
            .collect()
    }

    /// The lambda law this names (tables are read through the scene's path resolver).
    pub fn build(&self, ctx: &Context) -> Result<Lambda> {
        Ok(match self {
            LambdaSpec::Named(s) if s == "pi" => Lambda::Pi,
            LambdaSpec::Named(s) if s == "cut" => Lambda::Cut,
            LambdaSpec::Named(s) if s == "calibrated" => Lambda::Table(
                LambdaTable::from_csv(DEFAULT_LAMBDA_CSV).ctx("embedded lambda table")?,
            ),
            LambdaSpec::Named(s) => {
                let path = ctx.resolve(s);
                let text = std::fs::read_to_string(&path).map_err(crate::error::io_err(
                    format!("reading lambda table {}", path.display()),
                ))?;
                Lambda::Table(
                    LambdaTable::from_csv(&text).ctx(format!("lambda table {}", path.display()))?,
                )
            }
            LambdaSpec::Value(v) => Lambda::Value(*v),
        })
    }
}

/// lambda = pi alone, the default of the kinds that take a list of lambdas.
pub(crate) fn default_lambdas() -> Vec<LambdaSpec> {
    vec![LambdaSpec::default()]
}
