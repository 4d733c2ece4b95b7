//! The stochastic collision equation, Eqs. (3)-(7) of Giese (issue 6, in progress).
