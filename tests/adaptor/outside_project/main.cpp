// One tet carrying f = z rendered through the installed adaptor; exits non-zero on failure.
#include <tetray/adaptor.hpp>

#include <cstdio>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  const std::string out = argc > 1 ? argv[1] : "outside_out";
  tetray::Status status;
  auto adaptor = tetray::Adaptor::create_from_yaml(
      MPI_COMM_WORLD,
      "output: {directory: " + out +
          ", formats: [png], quiet: true}\n"
          "scenes: [{name: tet, field: f, isovalues: [0.5], image: {width: 16, height: 16}}]\n",
      status);
  if (adaptor) {
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const std::vector<std::int64_t> tets = {0, 1, 2, 3};
    const std::vector<double> f = {0, 0, 0, 1};
    const tetray::FieldView fields[] = {tetray::FieldView::of("f", f)};
    status =
        adaptor->execute(0, 0, {tetray::PointsView::of(xyz), tetray::TetsView::of(tets)}, fields);
    if (status.ok()) status = adaptor->finalize();
  }
  if (!status.ok()) std::fprintf(stderr, "outside_solver: %s\n", status.message.c_str());
  adaptor.reset();
  MPI_Finalize();
  return status.ok() ? 0 : 1;
}
