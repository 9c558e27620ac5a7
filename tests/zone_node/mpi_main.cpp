// GoogleTest main for tests that touch MPI: MPI_Init once as a singleton (no mpirun needed).
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdlib>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // ctest runs many singletons at once. Open MPI 4.1 creates its session directory
  // (/tmp/ompi.HOST.UID) with a check-then-mkdir that two starting processes can race, failing
  // one with "File exists"; a directory of its own per process has no one to race. Under
  // mpirun the launcher has made the session directory already.
  std::string session_root;
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("OMPI_MCA_orte_tmpdir_base")) {
    std::string pattern = (std::filesystem::temp_directory_path() / "zonesim-mpi-XXXXXX").string();
    if (mkdtemp(pattern.data())) {
      session_root = pattern;
      setenv("OMPI_MCA_orte_tmpdir_base", session_root.c_str(), 1);
    }
  }
  MPI_Init(&argc, &argv);
  int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  if (!session_root.empty()) {
    std::error_code ignored;  // what Open MPI left there is ours alone
    std::filesystem::remove_all(session_root, ignored);
  }
  return rc;
}
