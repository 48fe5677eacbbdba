"""Writes the archives of tests/cli (run here with python3): the members of
two_meshes.zip (cube.obj, sub/tet.off, README.txt) as a tar compressed by
gzip (.tar.gz and .tgz) and by bzip2 (.tar.bz2), a tar whose mesh has a
name longer than 100 characters (pax header), and the cube alone as
cube.obj.bz2."""
import bz2
import io
import tarfile
import zipfile

with zipfile.ZipFile("two_meshes.zip") as z:
    members = [(n, z.read(n)) for n in z.namelist()]


def tar(path, mode, entries, fmt=tarfile.USTAR_FORMAT):
    with tarfile.open(path, mode, format=fmt) as t:
        for name, data in entries:
            info = tarfile.TarInfo(name)
            info.size = len(data)
            info.mtime = 1795737600  # fixed, so the files do not change when remade
            t.addfile(info, io.BytesIO(data))


tar("two_meshes.tar.gz", "w:gz", members)
tar("two_meshes.tgz", "w:gz", members)
tar("two_meshes.tar.bz2", "w:bz2", members)
tar("long_name.tar", "w", [("d" * 60 + "/" + "e" * 60 + "/cube.obj", members[0][1])], tarfile.PAX_FORMAT)
with open("cube.obj.bz2", "wb") as f:
    f.write(bz2.compress(members[0][1]))
