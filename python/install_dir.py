"""Prints where `cmake --install` puts the module, relative to the install prefix (argv[1]): the
interpreter's platform site-packages path (on Debian with prefix /usr/local:
lib/python3.X/dist-packages) when it lies under the prefix, else lib/python3.X/site-packages."""
import os
import sys
import sysconfig

prefix = os.path.abspath(sys.argv[1])
platlib = os.path.abspath(sysconfig.get_path("platlib"))
if os.path.commonpath([platlib, prefix]) == prefix:
    print(os.path.relpath(platlib, prefix))
else:
    print(sysconfig.get_path("platlib", "posix_prefix", vars={"base": "", "platbase": ""}).lstrip("/"))
