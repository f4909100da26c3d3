#pragma once
// Where the fuzz targets write an input as the file a reader needs: in memory (/dev/shm)
// where the machine has it, so that a run is not timed by the disk.
#include <string>
#include <sys/stat.h>

inline std::string fuzzFolder()
{
  struct stat folder;
  return ::stat("/dev/shm", &folder) == 0 && S_ISDIR(folder.st_mode) ? "/dev/shm" : "/tmp";
}
