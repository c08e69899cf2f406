#pragma once
// Little-endian, unpadded binary reading and writing for the GPU check's
// query files (ray_cast_query_file.h, sact_query_file.h): a value, or an
// array whose length the caller knows. Plain C++17, for nvcc as well.
#include <fstream>
#include <string>
#include <vector>

namespace rc::gpu_check {

namespace binary_io {
template <typename T>
void Put(std::ofstream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <typename T>
void PutArray(std::ofstream& out, const std::vector<T>& values) {
  out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(T)));
}
template <typename T>
bool Get(std::ifstream& in, T* value) {
  return static_cast<bool>(in.read(reinterpret_cast<char*>(value), sizeof(T)));
}
template <typename T>
bool GetArray(std::ifstream& in, std::size_t count, std::vector<T>* values) {
  values->resize(count);
  return static_cast<bool>(
      in.read(reinterpret_cast<char*>(values->data()), static_cast<std::streamsize>(count * sizeof(T))));
}
inline bool Fail(std::string* error, const std::string& path, const std::string& what) {
  if (error) *error = path + ": " + what;
  return false;
}
}  // namespace binary_io

}  // namespace rc::gpu_check
