//! A solver on the periodic or on the free half-space, as the class's constructor chose:
//! one type for the class to hold, and one match for every method that forwards to it.

/// `P` (a solver on `PeriodicHalfSpace`) or `F` (the same solver on
/// `NonPeriodicHalfSpace`).
pub enum OnOperator<P, F> {
    Periodic(P),
    Free(F),
}

/// `on_operator!(value, s => expr)`: `expr` with `s` bound to the solver `value` holds,
/// whichever half-space it is on.
macro_rules! on_operator {
    ($value:expr, $s:ident => $body:expr) => {
        match $value {
            $crate::on_operator::OnOperator::Periodic($s) => $body,
            $crate::on_operator::OnOperator::Free($s) => $body,
        }
    };
}

/// `built_on!(frame, e_star, op => expr)`: `expr` with `op` bound to the periodic or the
/// free half-space of the grid `frame` (a `contact::Frame`) and modulus `e_star`, as
/// [`OnOperator`]; in a function returning `bem3d::Result`, whose error an operator
/// that cannot be built returns.
macro_rules! built_on {
    ($frame:expr, $e_star:expr, $op:ident => $body:expr) => {{
        let frame = $frame;
        let ((ny, nx), (lx, ly)) = (frame.shape, frame.size);
        if frame.periodic {
            let $op = bem3d::PeriodicHalfSpace::try_new(nx, ny, lx, ly, $e_star)?;
            $crate::on_operator::OnOperator::Periodic($body)
        } else {
            let $op = bem3d::NonPeriodicHalfSpace::try_new(nx, ny, lx, ly, $e_star)?;
            $crate::on_operator::OnOperator::Free($body)
        }
    }};
}
