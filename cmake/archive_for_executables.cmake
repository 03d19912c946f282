# Some Debian libraries cost every process that loads their shared object at its start: static
# initialisers (pagmo: 0.058 s, 32 MB), or dependencies that cdem never calls (HDF5: libcurl and
# 25 more for its S3 driver). Their static archives bring in only the objects a program calls,
# but Debian builds them position-independent for executables only, so a shared object (the
# Python extension) must keep the shared library (docs/performance.md "Session 57").
#
# cdem_archive_for_executables(<out> <archive> <shared>) sets <out> to a link item that names the
# target <archive> for an executable and the target <shared> for anything else; a library links
# it and its consumers get the one that fits them.
function(cdem_archive_for_executables out archive shared)
  set(${out} "$<IF:$<STREQUAL:$<TARGET_PROPERTY:TYPE>,EXECUTABLE>,${archive},${shared}>"
      PARENT_SCOPE)
endfunction()
