"""Two traces in two Python threads, at once (each releases the GIL), give the bytes of
the same two traces one after the other."""

import threading

import irsig
from conftest import MATERIALS, small_view


def test_two_threads_give_the_bytes_of_one_after_the_other(scene_raw, tmp_path):
    views = [small_view(tmp_path, 96, 72, "a.ron"), small_view(tmp_path, 80, 60, "b.ron")]
    options = dict(band="8-14", atmosphere="us-std-1976", supersample=2)
    alone = [irsig.trace(scene_raw, MATERIALS, v, **options).files for v in views]
    together = [None, None]

    def run(i):
        together[i] = irsig.trace(scene_raw, MATERIALS, views[i], threads=1, **options).files

    threads = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert together == alone
    assert set(alone[0]) >= {"radiance.exr", "truth.exr", "map.png", "dc.png", "lut.txt"}
