#include "pqPointCloudBilateralReadOutWidget.h"

#include "pqCoreUtilities.h"
#include "pqDoubleLineEdit.h"
#include "vtkCommand.h"
#include "vtkSMDoubleVectorProperty.h"
#include "vtkSMIdTypeVectorProperty.h"
#include "vtkSMIntVectorProperty.h"
#include "vtkSMProperty.h"
#include "vtkSMStringVectorProperty.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QStringList>

pqPointCloudBilateralReadOutWidget::pqPointCloudBilateralReadOutWidget(vtkSMProxy* proxy,
  vtkSMProperty* property,
  QWidget* parent)
  : Superclass(proxy, parent)
  , Text(new QLabel(this))
{
  this->setProperty(property);
  this->setChangeAvailableAsChangeFinished(true);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  this->Text->setObjectName("ReadOut");
  this->Text->setWordWrap(true);
  this->Text->setTextFormat(Qt::PlainText);
  // The panel gives an information property's widget a stylesheet that paints it as an edit
  // field (the Base colour): this label, which covers the widget, keeps the panel's colour.
  this->Text->setStyleSheet("QLabel { background-color: palette(window); }");
  layout->addWidget(this->Text);
  pqCoreUtilities::connect(property, vtkCommand::ModifiedEvent, this, SLOT(showValues()));
  this->showValues();
}

pqPointCloudBilateralReadOutWidget::~pqPointCloudBilateralReadOutWidget() = default;

QString pqPointCloudBilateralReadOutWidget::FormatValues(vtkSMProperty* property)
{
  QStringList values;
  if (auto* strings = vtkSMStringVectorProperty::SafeDownCast(property))
  {
    for (unsigned int i = 0; i < strings->GetNumberOfElements(); ++i)
    {
      values << QString::fromUtf8(strings->GetElement(i));
    }
  }
  else if (auto* doubles = vtkSMDoubleVectorProperty::SafeDownCast(property))
  {
    for (unsigned int i = 0; i < doubles->GetNumberOfElements(); ++i)
    {
      values << pqDoubleLineEdit::formatDoubleUsingGlobalPrecisionAndNotation(
        doubles->GetElement(i));
    }
  }
  else if (auto* ints = vtkSMIntVectorProperty::SafeDownCast(property))
  {
    for (unsigned int i = 0; i < ints->GetNumberOfElements(); ++i)
    {
      values << QString::number(ints->GetElement(i));
    }
  }
  else if (auto* ids = vtkSMIdTypeVectorProperty::SafeDownCast(property))
  {
    for (unsigned int i = 0; i < ids->GetNumberOfElements(); ++i)
    {
      values << QString::number(ids->GetElement(i));
    }
  }
  return values.join("  ");
}

void pqPointCloudBilateralReadOutWidget::showValues()
{
  this->Text->setText(FormatValues(this->property()));
}
