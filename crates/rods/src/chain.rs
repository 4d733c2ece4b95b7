//! Rod-chain molecular dynamics of the Hamiltonian Eq. (2) of Giese (issue 6, in progress).
