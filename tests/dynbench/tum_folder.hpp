#pragma once
// A small TUM-format folder in the renderer's layout (rgb/, depth/, rgb.txt, depth.txt,
// groundtruth.txt, objects/, masks/<variant>/), made from the embedded fr1/xyz frames with the
// front end's composited person: the tests' stand-in for a rendered sequence.

#include <string>

namespace hbos_test {

/// Writes the first `frames` embedded frames with the person composited into `dir`: objects/
/// holds id 1 on the person, masks/perfect/ its exact silhouette and masks/eroded/ the
/// silhouette eroded by 6 px, both in DynaSLAM's convention (0 = dynamic, 255 = static).
void write_tum_folder(const std::string& dir, int frames);

/// The stem (file name without extension) of frame `index`'s colour image in such a folder.
std::string frame_stem(const std::string& dir, int index);

}  // namespace hbos_test
